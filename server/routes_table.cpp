#include "routes_table.hpp"

#include "api/openapi.hpp"

namespace tourmap::server {

void register_routes(ServerState& state, api::AppContext& ctx, EventHub& events, CrowdStreamer& crowd) {
  api::add_api_routes(state.router, ctx);
  state.router.add("GET", "/metrics", api::Exec::io, [&state](api::Request&) {
    api::Response r;
    r.content_type = "text/plain; version=0.0.4; charset=utf-8";
    r.body = state.metrics.render();
    return r;
  });
  state.router.add("GET", "/api/v1/openapi.yaml", api::Exec::io, [](api::Request&) {
    api::Response r;
    r.content_type = "application/yaml";
    r.body = std::string(api::openapi_yaml());
    r.cacheable = true;
    return r;
  });
  state.ws_endpoints["/api/v1/events"] = events.endpoint();
  state.ws_endpoints["/api/v1/crowd/stream"] = crowd.endpoint();
}

std::vector<std::pair<std::string, std::string>> registered_routes() {
  // A throwaway server state: handlers are registered, never run, and nothing is opened.
  Config config = default_config();
  config.access_log = "off";
  config.compute_threads = 1;
  ServerState state(config);
  store::DbPool db(":memory:");
  api::Catalog catalog(db);
  api::DeformService deform(catalog);
  api::MetroService metro(catalog);
  api::AppContext ctx{db, catalog, deform, metro, "routes"};
  boost::asio::io_context ioc;
  EventHub events(ioc, db, std::chrono::milliseconds(1000));
  api::CrowdAssets assets(config.data_dir + "/models", nullptr);
  CrowdStreamer crowd(assets, ctx.crowd_limits);  // never started: no render thread
  register_routes(state, ctx, events, crowd);
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& r : state.router.routes()) out.emplace_back(r.method, r.pattern);
  for (const auto& [path, ep] : state.ws_endpoints) out.emplace_back("WS", path);
  return out;
}

}  // namespace tourmap::server
