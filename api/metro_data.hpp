#pragma once
// What the metro computations need from a city, derived once per city version (the
// computation is core's, metro/city_input.hpp): the network in the city's projection (metres),
// and per POI its position, its distance to the nearest station and its prominence signals;
// here with the city it came from and its cache key.

#include "catalog.hpp"

#include "metro/city_input.hpp"
#include "metro/layout_graph.hpp"
#include "metro/visual_worth.hpp"

#include <memory>
#include <string>
#include <vector>

namespace tourmap::api {

// Where POI ranks come from (paper 5.4.1: r_i); see metro/city_input.hpp.
using RankSource = metro::RankSource;

// projection, graph, poi_xy, poi_station_km, has_rank, station_count: metro::CityMetroInput.
struct CityMetroData : metro::CityMetroInput {
  std::shared_ptr<const model::City> city;
  std::string key;  // "<city>@<version>"
};

std::shared_ptr<const CityMetroData> make_city_metro_data(std::shared_ptr<const model::City> city);

// ApiError 400 (field "rank") when `data` is asked for and the city's POIs carry no rank.
void check_rank_source(const CityMetroData& d, RankSource source);

// r_i in (0, 1] per POI for a rank source; throws ApiError (field "rank") when `data` is asked
// for and the city has none.
std::vector<double> poi_ranks(const CityMetroData& d, RankSource source);

// The visual worth field over a city's POIs.
metro::VisualWorth make_visual_worth(const CityMetroData& d, RankSource source, const metro::WorthParams& params);

}  // namespace tourmap::api
