#include "metro_data.hpp"

#include "http.hpp"

namespace tourmap::api {

std::shared_ptr<const CityMetroData> make_city_metro_data(std::shared_ptr<const model::City> city) {
  auto d = std::make_shared<CityMetroData>();
  // The network projected, and per POI the proximity rho_i (nearest station: kd-tree, then the
  // geodesic distance).
  static_cast<metro::CityMetroInput&>(*d) = metro::make_city_metro_input(city->metro, city->pois, city->info.projection);
  d->city = city;
  d->key = city->info.id + "@" + std::to_string(city->info.version);
  return d;
}

void check_rank_source(const CityMetroData& d, RankSource source) {
  if (source == RankSource::data && !d.has_rank)
    throw ApiError(400, "invalid_parameter", "rank: the POIs of this city carry no rank or popularity", "rank");
}

std::vector<double> poi_ranks(const CityMetroData& d, RankSource source) {
  check_rank_source(d, source);
  return metro::poi_ranks(d.city->pois, d.has_rank, source);
}

metro::VisualWorth make_visual_worth(const CityMetroData& d, RankSource source, const metro::WorthParams& params) {
  check_rank_source(d, source);
  return metro::make_visual_worth(d, d.city->pois, source, params);
}

}  // namespace tourmap::api
