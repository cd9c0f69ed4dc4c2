// The metro map endpoints (paper ch. 5): layout, visual worth, POI clusters.

#include "routes.hpp"

namespace tourmap::api {

void add_metro_routes(Router& router, AppContext& ctx) {
  router.add("GET", "/api/v1/cities/{id}/layout", Exec::heavy,
             [&ctx](Request& req) { return ctx.metro.layout(req, false); });
  router.add("POST", "/api/v1/cities/{id}/layout", Exec::heavy,
             [&ctx](Request& req) { return ctx.metro.layout(req, true); });
  router.add("GET", "/api/v1/cities/{id}/visual-worth", Exec::heavy,
             [&ctx](Request& req) { return ctx.metro.visual_worth(req); });
  router.add("GET", "/api/v1/cities/{id}/clusters", Exec::heavy,
             [&ctx](Request& req) { return ctx.metro.clusters(req); });
}

}  // namespace tourmap::api
