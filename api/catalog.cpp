#include "catalog.hpp"

#include "store/repo.hpp"

namespace tourmap::api {

std::shared_ptr<const model::City> Catalog::city(const std::string& id) {
  auto db = pool_.acquire();
  auto version = store::city_version(*db, id);
  std::lock_guard lock(mutex_);
  if (!version) {
    cities_.erase(id);
    return nullptr;
  }
  auto it = cities_.find(id);
  if (it != cities_.end() && it->second->info.version == *version) return it->second;
  // Loading under the lock keeps two requests from loading the same city twice; loads are
  // milliseconds for a city.
  auto loaded = store::load_city(*db, id);
  if (!loaded) return nullptr;
  auto shared = std::make_shared<const model::City>(std::move(*loaded));
  cities_[id] = shared;
  return shared;
}

std::shared_ptr<const RoadNetworkEntry> Catalog::road_network(const std::string& id) {
  auto db = pool_.acquire();
  auto info = store::find_road_network(*db, id);
  std::lock_guard lock(mutex_);
  if (!info) {
    roads_.erase(id);
    return nullptr;
  }
  auto it = roads_.find(id);
  if (it != roads_.end() && it->second->info.version == info->version) return it->second;
  auto net = store::load_road_network(*db, id);
  if (!net) return nullptr;
  auto entry = std::make_shared<RoadNetworkEntry>();
  entry->info = *info;
  entry->net = std::move(*net);
  roads_[id] = entry;
  return entry;
}

}  // namespace tourmap::api
