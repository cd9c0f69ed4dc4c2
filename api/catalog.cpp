#include "catalog.hpp"

#include "store/repo.hpp"

#include <stdexcept>

namespace tourmap::api {

namespace {

// The network and its info as of one version: an import committing between the two reads
// changes the version (versions only grow), and the pair is read again.
std::shared_ptr<const RoadNetworkEntry> read_road_entry(store::Db& db, const std::string& id) {
  for (int attempt = 0; attempt < 3; ++attempt) {
    auto before = store::find_road_network(db, id);
    auto net = store::load_road_network(db, id);
    auto context = store::load_road_context(db, id);
    auto after = store::find_road_network(db, id);
    if (!before || !net || !after) return nullptr;  // deleted meanwhile
    if (before->version != after->version) continue;
    auto entry = std::make_shared<RoadNetworkEntry>();
    entry->info = std::move(*after);
    entry->net = std::move(*net);
    entry->context = std::move(context);
    return entry;
  }
  throw std::runtime_error("road network '" + id + "' kept changing while it was read");
}

}  // namespace

std::shared_ptr<const RoadNetworkEntry> Catalog::load_road_entry(const std::string& id) {
  auto db = pool_.acquire();
  return read_road_entry(*db, id);
}

std::shared_ptr<const model::City> Catalog::city(const std::string& id) {
  std::optional<std::int64_t> version;
  {
    auto db = pool_.acquire();
    version = store::city_version(*db, id);
  }
  {
    std::lock_guard lock(mutex_);
    if (!version) {
      cities_.erase(id);
      return nullptr;
    }
    auto it = cities_.find(id);
    if (it != cities_.end() && it->second->info.version == *version) return it->second;
  }
  auto loaded = city_loads_.run(id + "@" + std::to_string(*version), [&]() -> std::shared_ptr<const model::City> {
    auto db = pool_.acquire();
    auto city = store::load_city(*db, id);
    if (!city) return nullptr;  // deleted meanwhile
    return std::make_shared<const model::City>(std::move(*city));
  });
  if (!loaded) return nullptr;
  std::lock_guard lock(mutex_);
  auto& slot = cities_[id];
  if (!slot || slot->info.version < loaded->info.version) slot = loaded;  // never go back a version
  return loaded;
}

std::shared_ptr<const RoadNetworkEntry> Catalog::road_network(const std::string& id) {
  std::optional<model::RoadNetworkInfo> info;
  {
    auto db = pool_.acquire();
    info = store::find_road_network(*db, id);
  }
  {
    std::lock_guard lock(mutex_);
    if (!info) {
      roads_.erase(id);
      return nullptr;
    }
    auto it = roads_.find(id);
    if (it != roads_.end() && it->second->info.version == info->version) return it->second;
  }
  auto loaded = road_loads_.run(id + "@" + std::to_string(info->version), [&] { return load_road_entry(id); });
  if (!loaded) return nullptr;
  std::lock_guard lock(mutex_);
  auto& slot = roads_[id];
  if (!slot || slot->info.version < loaded->info.version) slot = loaded;
  return loaded;
}

}  // namespace tourmap::api
