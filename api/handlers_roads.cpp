// Road networks: list and GeoJSON (optionally clipped to a bbox).

#include "geojson.hpp"
#include "params.hpp"
#include "road_context.hpp"
#include "routes.hpp"

#include "store/repo.hpp"

namespace tourmap::api {

void add_road_routes(Router& router, AppContext& ctx) {
  router.add("GET", "/api/v1/roads", Exec::light, [&ctx](Request&) {
    auto db = ctx.db.acquire();
    nlohmann::json roads = nlohmann::json::array();
    for (const auto& info : store::list_road_networks(*db)) roads.push_back(road_network_summary(info));
    Response r = json_response({{"roads", std::move(roads)}});
    r.cacheable = true;  // no max-age: clients revalidate (cheap 304) and see imports at once
    return r;
  });

  router.add("GET", "/api/v1/roads/{id}", Exec::light, [&ctx](Request& req) {
    auto bbox = query_bbox(req);
    bool with_nodes = query_bool(req, "nodes", false);
    const std::string format = query_choice(req, "format", {"geojson", "topology"}, "geojson");
    if (format == "topology" && bbox) throw bad("bbox", "not available with format=topology (whole networks only)");
    const auto& id = req.param("id");
    require_slug(id, "road network");
    auto entry = ctx.catalog.road_network(id);
    if (!entry) throw not_found("id", "road network", id);
    Response r;
    if (format == "topology") {
      r = json_response(roads_topology(*entry));
    } else {
      r.content_type = "application/geo+json";
      r.body = roads_geojson(*entry, bbox, with_nodes);
    }
    r.cacheable = true;  // no max-age: clients revalidate (cheap 304) and see imports at once
    return r;
  });

  // The context layers drawn under the roads (sea, water, parks, land use, buildings, rivers,
  // railways, place names), imported from the same extract.
  router.add("GET", "/api/v1/roads/{id}/context", Exec::light, [&ctx](Request& req) {
    const auto q = parse_context_query(req);
    const auto& id = req.param("id");
    require_slug(id, "road network");
    auto entry = ctx.catalog.road_network(id);
    if (!entry) throw not_found("id", "road network", id);
    Response r = json_response(road_context_json(*entry, q));
    r.cacheable = true;
    return r;
  });
}

}  // namespace tourmap::api
