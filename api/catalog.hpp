#pragma once
// In-memory copies of cities and road networks, reloaded when their version in the store
// changes. A city or network imported while the server runs (by another process, even) is
// served on the next request, without a restart. Loads run outside the catalog's lock (a big
// road network takes ~200 ms), one per (id, version) at a time: other ids are served meanwhile.

#include "single_flight.hpp"

#include "store/db_pool.hpp"

#include "model/city.hpp"
#include "model/context.hpp"
#include "model/road.hpp"

#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace tourmap::api {

struct RoadNetworkEntry {
  model::RoadNetworkInfo info;
  model::RoadNetwork net;
  model::ContextLayers context;  // from the same extract (store/context_repo.cpp)
};

class Catalog {
 public:
  explicit Catalog(store::DbPool& pool) : pool_(pool) {}

  // Current city, or nullptr when there is none with that id.
  std::shared_ptr<const model::City> city(const std::string& id);
  std::shared_ptr<const RoadNetworkEntry> road_network(const std::string& id);

  store::DbPool& pool() { return pool_; }

 private:
  std::shared_ptr<const RoadNetworkEntry> load_road_entry(const std::string& id);

  store::DbPool& pool_;
  std::mutex mutex_;  // guards the two maps only
  std::map<std::string, std::shared_ptr<const model::City>> cities_;
  std::map<std::string, std::shared_ptr<const RoadNetworkEntry>> roads_;
  SingleFlight<std::shared_ptr<const model::City>> city_loads_;
  SingleFlight<std::shared_ptr<const RoadNetworkEntry>> road_loads_;
};

}  // namespace tourmap::api
