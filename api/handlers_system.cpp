// GET /healthz and GET /api/v1: liveness with a store check, and the API index.

#include "routes.hpp"

#include "store/migrate.hpp"

namespace tourmap::api {

void add_system_routes(Router& router, AppContext& ctx) {
  // Runs on the IO threads so that it answers even when the compute pool is saturated.
  router.add("GET", "/healthz", Exec::io, [&ctx](Request&) {
    auto uptime = std::chrono::duration<double>(std::chrono::steady_clock::now() - ctx.started).count();
    try {
      auto db = ctx.db.acquire();
      int schema = store::schema_version(*db);
      return json_response({{"status", "ok"}, {"version", ctx.version}, {"schema_version", schema},
                            {"uptime_s", uptime}});
    } catch (const std::exception& e) {
      return json_response({{"status", "unavailable"},
                            {"version", ctx.version},
                            {"error", error_object("store_unavailable", std::string("the store: ") + e.what())}},
                           503);
    }
  });

  router.add("GET", "/api/v1", Exec::io, [&ctx](Request&) {
    Response r = json_response({{"name", "tourmap"},
                                {"version", ctx.version},
                                {"spec", "/api/v1/openapi.yaml"},
                                {"endpoints", {"/api/v1/cities", "/api/v1/cities/{id}", "/api/v1/cities/{id}/metro",
                                               "/api/v1/cities/{id}/pois", "/api/v1/cities/{id}/pois/query",
                                               "/api/v1/cities/{id}/pois/{poi}/walk",
                                               "/api/v1/cities/{id}/layout", "/api/v1/cities/{id}/layout/roads",
                                               "/api/v1/cities/{id}/visual-worth",
                                               "/api/v1/cities/{id}/clusters",
                                               "/api/v1/roads", "/api/v1/roads/{id}", "/api/v1/roads/{id}/context",
                                               "/api/v1/deform/focus",
                                               "/api/v1/deform/mental", "/api/v1/deform/destination",
                                               "/api/v1/events", "/api/v1/crowd/scenes", "/api/v1/crowd/stream",
                                               "/healthz", "/metrics"}}});
    r.cacheable = true;
    return r;
  });
}

}  // namespace tourmap::api
