#include "metro_data.hpp"

#include "http.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_2.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/property_map.h>

#include <tuple>

namespace tourmap::api {

std::shared_ptr<const CityMetroData> make_city_metro_data(std::shared_ptr<const model::City> city) {
  auto d = std::make_shared<CityMetroData>();
  d->city = city;
  d->key = city->info.id + "@" + std::to_string(city->info.version);
  d->projection = city->info.projection;
  const auto& net = city->metro;
  d->graph = metro::layout_graph_of(net, d->projection);  // lengths are set per request

  // Nearest station per POI: kd-tree in the plane, then the geodesic distance.
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Point = Kernel::Point_2;
  using PointAndIndex = std::tuple<Point, std::uint32_t>;
  using Traits = CGAL::Search_traits_adapter<PointAndIndex, CGAL::Nth_of_tuple_property_map<0, PointAndIndex>,
                                             CGAL::Search_traits_2<Kernel>>;
  using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
  Search::Tree stations;
  for (std::uint32_t i = 0; i < net.nodes.size(); ++i)
    if (net.nodes[i].is_station()) stations.insert({Point(d->graph.pos[i].x, d->graph.pos[i].y), i});
  stations.build();
  for (const auto& p : city->pois) {
    auto xy = geo::project(d->projection, p.pos);
    d->poi_xy.push_back(xy);
    double km = 0;
    if (!stations.empty()) {
      Search nearest(stations, Point(xy.x, xy.y), 1);
      km = geo::geodesic_distance_m(p.pos, net.nodes[std::get<1>(nearest.begin()->first)].pos) / 1000.0;
    }
    d->poi_station_km.push_back(km);
    d->has_rank = d->has_rank || p.rank.has_value() || p.popularity.has_value();
  }
  return d;
}

std::vector<double> poi_ranks(const CityMetroData& d, RankSource source) {
  const auto& pois = d.city->pois;
  if (source == RankSource::automatic) source = d.has_rank ? RankSource::data : RankSource::proxy;
  std::vector<double> score(pois.size(), 0.0);
  switch (source) {
    case RankSource::data:
      if (!d.has_rank)
        throw ApiError(400, "invalid_parameter", "rank: the POIs of this city carry no rank or popularity", "rank");
      // A rank of 1 is the most prominent; popularity counts up. POIs without either come last.
      for (std::size_t i = 0; i < pois.size(); ++i)
        score[i] = pois[i].rank ? 1e9 - *pois[i].rank : pois[i].popularity ? *pois[i].popularity : -1e18;
      break;
    case RankSource::proxy:
      for (std::size_t i = 0; i < pois.size(); ++i)
        score[i] = 3.0 * !pois[i].wikipedia.empty() + 1.0 * !pois[i].image_url.empty() + 0.5 * !pois[i].url.empty();
      break;
    case RankSource::uniform:
      return std::vector<double>(pois.size(), 1.0);
    case RankSource::automatic:
      break;
  }
  return metro::ranks01_from_scores(score);
}

metro::VisualWorth make_visual_worth(const CityMetroData& d, RankSource source, const metro::WorthParams& params) {
  auto ranks = poi_ranks(d, source);
  std::vector<metro::WorthSource> sources;
  sources.reserve(d.poi_xy.size());
  for (std::size_t i = 0; i < d.poi_xy.size(); ++i) sources.push_back({d.poi_xy[i], ranks[i], d.poi_station_km[i]});
  return metro::VisualWorth(std::move(sources), params);
}

}  // namespace tourmap::api
