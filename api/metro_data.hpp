#pragma once
// What the metro computations need from a city, derived once per city version: the network in
// the city's projection (metres), the stations' kd-index, and per POI its position, its
// distance to the nearest station (geodesic, GeographicLib) and its prominence signals.

#include "catalog.hpp"

#include "metro/layout_graph.hpp"
#include "metro/visual_worth.hpp"

#include <memory>
#include <string>
#include <vector>

namespace tourmap::api {

// Where POI ranks come from (paper 5.4.1: r_i).
enum class RankSource {
  automatic,  // the data's rank or popularity when the city's POIs have one, else the proxy
  data,       // the data's rank (or popularity)
  proxy,      // Wikipedia/Wikidata link 3, image 1, website 0.5 (ties: input order)
  uniform,    // every POI the same rank
};

struct CityMetroData {
  std::shared_ptr<const model::City> city;
  geo::LocalProjection projection;
  metro::LayoutGraph graph;          // positions in metres; min_length left for each layout
  std::vector<geo::XY> poi_xy;       // metres
  std::vector<double> poi_station_km;  // geodesic distance to the nearest station
  bool has_rank = false;             // some POI has a rank or popularity in the data
  std::string key;                   // "<city>@<version>"
};

std::shared_ptr<const CityMetroData> make_city_metro_data(std::shared_ptr<const model::City> city);

// r_i in (0, 1] per POI for a rank source; throws ApiError (field "rank") when `data` is asked
// for and the city has none.
std::vector<double> poi_ranks(const CityMetroData& d, RankSource source);

// The visual worth field over a city's POIs.
metro::VisualWorth make_visual_worth(const CityMetroData& d, RankSource source, const metro::WorthParams& params);

}  // namespace tourmap::api
