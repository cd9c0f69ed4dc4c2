// The metro map endpoints (paper ch. 5): layout, visual worth, POI clusters, and the map as a
// file (issue 14).

#include "map_export.hpp"
#include "poi_walk.hpp"
#include "routes.hpp"
#include "schematic_roads.hpp"

#include <memory>

namespace tourmap::api {

void add_metro_routes(Router& router, AppContext& ctx) {
  router.add("GET", "/api/v1/cities/{id}/layout", Exec::heavy,
             [&ctx](Request& req) { return ctx.metro.layout(req, false); });
  router.add("POST", "/api/v1/cities/{id}/layout", Exec::heavy,
             [&ctx](Request& req) { return ctx.metro.layout(req, true); });
  // The streets in the schematic's space (issue 16): its cache lives with the route.
  auto roads = std::make_shared<SchematicRoadsService>(ctx.catalog, ctx.metro);
  router.add("GET", "/api/v1/cities/{id}/layout/roads", Exec::heavy,
             [roads](Request& req) { return roads->handle(req); });
  add_poi_walk_route(router, ctx);  // GET /cities/{id}/pois/{poi}/walk (issue 17)
  router.add("GET", "/api/v1/cities/{id}/visual-worth", Exec::heavy,
             [&ctx](Request& req) { return ctx.metro.visual_worth(req); });
  router.add("GET", "/api/v1/cities/{id}/clusters", Exec::heavy,
             [&ctx](Request& req) { return ctx.metro.clusters(req); });
  for (auto format : {MapFormat::svg, MapFormat::pdf, MapFormat::png})
    router.add("GET", std::string("/api/v1/cities/{id}/map.") + map_extension(format), Exec::heavy,
               [&ctx, format](Request& req) { return serve_map(ctx.metro, req, format); });
}

}  // namespace tourmap::api
