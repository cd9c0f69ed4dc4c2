#pragma once
// In-memory copies of cities and road networks, reloaded when their version in the store
// changes. A city or network imported while the server runs (by another process, even) is
// served on the next request, without a restart.

#include "store/db_pool.hpp"

#include "model/city.hpp"
#include "model/road.hpp"

#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace tourmap::api {

struct RoadNetworkEntry {
  model::RoadNetworkInfo info;
  model::RoadNetwork net;
};

class Catalog {
 public:
  explicit Catalog(store::DbPool& pool) : pool_(pool) {}

  // Current city, or nullptr when there is none with that id.
  std::shared_ptr<const model::City> city(const std::string& id);
  std::shared_ptr<const RoadNetworkEntry> road_network(const std::string& id);

  store::DbPool& pool() { return pool_; }

 private:
  store::DbPool& pool_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<const model::City>> cities_;
  std::map<std::string, std::shared_ptr<const RoadNetworkEntry>> roads_;
};

}  // namespace tourmap::api
