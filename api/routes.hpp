#pragma once
// Every API route tourmap serves, registered on a Router. The server adds only transport-level
// routes (/metrics) and static files.

#include "catalog.hpp"
#include "crowd_assets.hpp"
#include "crowd_view.hpp"
#include "deform_service.hpp"
#include "metro_service.hpp"
#include "router.hpp"

#include "load/import_limits.hpp"

#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

namespace tourmap::api {

// Handlers' events for WS /api/v1/events (an import's progress). Any thread may publish; once
// the server detaches its hub (before the hub goes) publishing does nothing.
class EventSink {
 public:
  void attach(std::function<void(const std::string&)> publish) {
    std::lock_guard lock(mutex_);
    publish_ = std::move(publish);
  }
  void detach() { attach(nullptr); }
  void publish(const std::string& message) {
    std::lock_guard lock(mutex_);
    if (publish_) publish_(message);
  }

 private:
  std::mutex mutex_;
  std::function<void(const std::string&)> publish_;
};

struct AppContext {
  store::DbPool& db;
  Catalog& catalog;
  DeformService& deform;
  MetroService& metro;
  std::string version;  // tourmap build version
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  CrowdAssets* crowd = nullptr;  // null: the crowd scenes list without triangle counts
  CrowdLimits crowd_limits{};
  load::ImportLimits import_limits{};  // what an upload may create (PUT imports)
  std::shared_ptr<EventSink> events = std::make_shared<EventSink>();
};

// Limits applied by the handlers (documented in openapi.yaml).
inline constexpr std::size_t kMaxPoiLimit = 10000;
inline constexpr std::size_t kDefaultPoiLimit = 1000;
inline constexpr std::size_t kMaxQueryCategories = 100;  // POST .../pois/query "categories"
inline constexpr std::size_t kMaxCategoryBytes = 200;

void add_system_routes(Router& router, AppContext& ctx);
void add_city_routes(Router& router, AppContext& ctx);
void add_road_routes(Router& router, AppContext& ctx);
void add_deform_routes(Router& router, AppContext& ctx);
void add_metro_routes(Router& router, AppContext& ctx);
void add_crowd_routes(Router& router, AppContext& ctx);
// Imports, deletes and cache purge: need an API key (Access::api_key).
void add_write_routes(Router& router, AppContext& ctx);

inline void add_api_routes(Router& router, AppContext& ctx) {
  add_system_routes(router, ctx);
  add_city_routes(router, ctx);
  add_road_routes(router, ctx);
  add_deform_routes(router, ctx);
  add_metro_routes(router, ctx);
  add_crowd_routes(router, ctx);
  add_write_routes(router, ctx);
}

}  // namespace tourmap::api
