#include "metro/city_input.hpp"

#include "geo/nearest_point_tree.hpp"

#include <stdexcept>
#include <tuple>

namespace tourmap::metro {

CityMetroInput make_city_metro_input(const model::MetroNetwork& net, const std::vector<model::Poi>& pois,
                                     const geo::LocalProjection& projection) {
  CityMetroInput d;
  d.projection = projection;
  d.graph = layout_graph_of(net, projection);  // lengths are set per layout
  d.station_count = net.station_count();
  for (const auto& node : net.nodes) {
    d.is_station.push_back(node.is_station());
    d.names.push_back(node.is_station() ? node.name : std::string());
  }

  // Proximity rho_i (5.4.1): nearest station per POI by a kd-tree in the plane, then the
  // geodesic distance to it.
  using geo::nearest::Point, geo::nearest::Search;
  geo::nearest::Tree stations;
  for (std::uint32_t i = 0; i < net.nodes.size(); ++i)
    if (net.nodes[i].is_station()) stations.insert({Point(d.graph.pos[i].x, d.graph.pos[i].y), i});
  stations.build();
  for (const auto& p : pois) {
    auto xy = geo::project(projection, p.pos);
    d.poi_xy.push_back(xy);
    double km = 0;
    if (!stations.empty()) {
      Search nearest(stations, Point(xy.x, xy.y), 1);
      km = geo::geodesic_distance_m(p.pos, net.nodes[std::get<1>(nearest.begin()->first)].pos) / 1000.0;
    }
    d.poi_station_km.push_back(km);
    d.has_rank = d.has_rank || p.rank.has_value() || p.popularity.has_value();
  }
  d.categories = poi::poi_categories(pois);
  return d;
}

RankSource resolve_rank_source(RankSource source, bool has_rank) {
  if (source != RankSource::automatic) return source;
  return has_rank ? RankSource::data : RankSource::proxy;
}

std::vector<double> poi_ranks(const std::vector<model::Poi>& pois, bool has_rank, RankSource source) {
  source = resolve_rank_source(source, has_rank);
  std::vector<double> score(pois.size(), 0.0);
  switch (source) {
    case RankSource::data:
      if (!has_rank) throw std::invalid_argument("the POIs of this city carry no rank or popularity");
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
  return ranks01_from_scores(score);
}

VisualWorth make_visual_worth(const CityMetroInput& in, const std::vector<model::Poi>& pois, RankSource source,
                              const WorthParams& params, const std::vector<double>& poi_weight) {
  auto ranks = poi_ranks(pois, in.has_rank, source);
  std::vector<WorthSource> sources;
  sources.reserve(in.poi_xy.size());
  for (std::size_t i = 0; i < in.poi_xy.size(); ++i)
    sources.push_back({in.poi_xy[i], ranks[i], in.poi_station_km[i], poi_weight.empty() ? 1.0 : poi_weight.at(i)});
  return VisualWorth(std::move(sources), params);
}

}  // namespace tourmap::metro
