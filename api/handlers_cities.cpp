// Cities: list, summary, metro network GeoJSON, POIs (GET with bbox, POST with a polygon).

#include "geojson.hpp"
#include "geojson_in.hpp"
#include "params.hpp"
#include "routes.hpp"

#include "store/repo.hpp"

#include <numeric>
#include <set>

namespace tourmap::api {
namespace {

std::shared_ptr<const model::City> require_city(AppContext& ctx, const Request& req) {
  const auto& id = req.param("id");
  require_slug(id, "city");
  auto city = ctx.catalog.city(id);
  if (!city) throw ApiError(404, "not_found", "no city '" + id + "'", "id");
  return city;
}

Response cacheable(Response r) {
  r.cacheable = true;  // no max-age: clients revalidate (cheap 304) and see imports at once
  return r;
}

std::vector<std::uint32_t> all_pois(const model::City& city) {
  std::vector<std::uint32_t> idx(city.pois.size());
  std::iota(idx.begin(), idx.end(), 0u);
  return idx;
}

}  // namespace

void add_city_routes(Router& router, AppContext& ctx) {
  router.add("GET", "/api/v1/cities", Exec::compute, [&ctx](Request&) {
    auto db = ctx.db.acquire();
    nlohmann::json cities = nlohmann::json::array();
    for (const auto& info : store::list_cities(*db)) cities.push_back(city_summary(info));
    return cacheable(json_response({{"cities", std::move(cities)}}));
  });

  router.add("GET", "/api/v1/cities/{id}", Exec::compute, [&ctx](Request& req) {
    auto city = require_city(ctx, req);
    auto body = city_summary(city->info);
    nlohmann::json lines = nlohmann::json::array();
    for (const auto& l : city->metro.lines) lines.push_back({{"id", l.id}, {"label", l.label}, {"color", l.color}});
    body["lines"] = std::move(lines);
    std::set<std::string> categories;
    for (const auto& p : city->pois)
      if (!p.category.empty()) categories.insert(p.category);
    body["poi_categories"] = categories;
    return cacheable(json_response(body));
  });

  router.add("GET", "/api/v1/cities/{id}/metro", Exec::compute, [&ctx](Request& req) {
    auto bbox = query_bbox(req);
    auto city = require_city(ctx, req);
    return cacheable(geojson_response(metro_geojson(*city, bbox)));
  });

  router.add("GET", "/api/v1/cities/{id}/pois", Exec::compute, [&ctx](Request& req) {
    auto bbox = query_bbox(req);
    PoiPage page;
    page.limit = static_cast<std::size_t>(query_int(req, "limit", 1, kMaxPoiLimit, kDefaultPoiLimit));
    page.offset = static_cast<std::size_t>(query_int(req, "offset", 0, 1'000'000'000, 0));
    auto city = require_city(ctx, req);
    return cacheable(geojson_response(pois_geojson(*city, bbox, all_pois(*city), page)));
  });

  // POIs inside a drawn area, optionally filtered by category: for mobile apps and the client.
  router.add("POST", "/api/v1/cities/{id}/pois/query", Exec::compute, [&ctx](Request& req) {
    auto body = parse_json_body(req);
    if (!body.is_object()) throw ApiError(400, "invalid_parameter", "body must be a JSON object", "body");
    std::optional<geo::BBox> bbox;
    if (body.contains("bbox")) bbox = parse_bbox_json(body["bbox"], "bbox");
    std::optional<geo::PolygonSet> within;
    if (body.contains("within")) within.emplace(parse_polygons(body["within"], "within"));
    std::set<std::string> categories;
    if (body.contains("categories")) {
      const auto& c = body["categories"];
      if (!c.is_array()) throw ApiError(400, "invalid_parameter", "categories: expected an array of strings", "categories");
      for (const auto& v : c) {
        if (!v.is_string())
          throw ApiError(400, "invalid_parameter", "categories: expected an array of strings", "categories");
        categories.insert(v.get<std::string>());
      }
    }
    PoiPage page;
    for (auto [name, target, min, max] : {std::tuple{"limit", &page.limit, std::size_t{1}, kMaxPoiLimit},
                                          std::tuple{"offset", &page.offset, std::size_t{0}, std::size_t{1'000'000'000}}}) {
      if (!body.contains(name)) continue;
      const auto& v = body[name];
      if (!v.is_number_integer() || v.get<long long>() < static_cast<long long>(min) ||
          v.get<long long>() > static_cast<long long>(max))
        throw ApiError(400, "invalid_parameter",
                       std::string(name) + ": expected an integer between " + std::to_string(min) + " and " +
                           std::to_string(max),
                       name);
      *target = v.get<std::size_t>();
    }
    for (auto it = body.begin(); it != body.end(); ++it)
      if (it.key() != "bbox" && it.key() != "within" && it.key() != "categories" && it.key() != "limit" &&
          it.key() != "offset")
        throw ApiError(400, "invalid_parameter", "unknown field '" + it.key() + "'", it.key());

    auto city = require_city(ctx, req);
    std::vector<std::uint32_t> selected;
    for (std::uint32_t i = 0; i < city->pois.size(); ++i) {
      const auto& p = city->pois[i];
      if (!categories.empty() && !categories.count(p.category)) continue;
      if (within && !within->contains(p.pos)) continue;
      selected.push_back(i);
    }
    return geojson_response(pois_geojson(*city, bbox, selected, page));
  });
}

}  // namespace tourmap::api
