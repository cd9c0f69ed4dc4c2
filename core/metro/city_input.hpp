#pragma once
// What the metro pipeline needs from a city, derived once per city version: the network in the
// city's projection (metres), per POI its position, its distance to the nearest station
// (geodesic, GeographicLib) and its prominence signals; and the POI ranks r_i (paper 5.4.1).

#include "metro/layout_graph.hpp"
#include "metro/visual_worth.hpp"
#include "model/metro.hpp"
#include "model/poi.hpp"
#include "poi/interests.hpp"

#include <string>
#include <vector>

namespace tourmap::metro {

// Where POI ranks come from (paper 5.4.1: r_i).
enum class RankSource {
  automatic,  // the data's rank or popularity when the city's POIs have one, else the proxy
  data,       // the data's rank (or popularity)
  proxy,      // Wikipedia/Wikidata link 3, image 1, website 0.5 (ties: input order)
  uniform,    // every POI the same rank
};

struct CityMetroInput {
  geo::LocalProjection projection;
  LayoutGraph graph;                   // positions in metres; min_length left for each layout
  std::vector<XY> poi_xy;              // metres
  std::vector<double> poi_station_km;  // geodesic distance to the nearest station (rho_i)
  bool has_rank = false;               // some POI has a rank or popularity in the data
  std::size_t station_count = 0;       // nodes that are stations (not junctions)
  std::vector<bool> is_station;        // per node
  std::vector<std::string> names;      // per node: the station's name (empty for a junction)
  poi::PoiCategories categories;       // the POIs' categories with counts (interests)
};

CityMetroInput make_city_metro_input(const model::MetroNetwork& net, const std::vector<model::Poi>& pois,
                                     const geo::LocalProjection& projection);

// `automatic` resolved for these POIs: data when they carry a rank, else proxy.
RankSource resolve_rank_source(RankSource source, bool has_rank);

// r_i in (0, 1] per POI; throws std::invalid_argument when `data` is asked for and no POI has a
// rank or popularity.
std::vector<double> poi_ranks(const std::vector<model::Poi>& pois, bool has_rank, RankSource source);

// The visual worth field (eq. 5.1) over a city's POIs; `poi_weight`: per POI its interest
// weight (poi/interests.hpp), empty for the paper's field.
VisualWorth make_visual_worth(const CityMetroInput& in, const std::vector<model::Poi>& pois, RankSource source,
                              const WorthParams& params, const std::vector<double>& poi_weight = {});

}  // namespace tourmap::metro
