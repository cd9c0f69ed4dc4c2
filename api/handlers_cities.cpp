// Cities: list, summary, metro network GeoJSON, POIs (GET with bbox, POST with a polygon).

#include "geojson.hpp"
#include "geojson_in.hpp"
#include "params.hpp"
#include "routes.hpp"
#include "schematic_roads.hpp"

#include "store/repo.hpp"

#include <numeric>
#include <set>

namespace tourmap::api {
namespace {

std::shared_ptr<const model::City> require_city(AppContext& ctx, const Request& req) {
  const auto& id = req.param("id");
  require_slug(id, "city");
  auto city = ctx.catalog.city(id);
  if (!city) throw not_found("id", "city", id);
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
  router.add("GET", "/api/v1/cities", Exec::light, [&ctx](Request&) {
    auto db = ctx.db.acquire();
    nlohmann::json cities = nlohmann::json::array();
    for (const auto& info : store::list_cities(*db)) cities.push_back(city_summary(info));
    return cacheable(json_response({{"cities", std::move(cities)}}));
  });

  router.add("GET", "/api/v1/cities/{id}", Exec::light, [&ctx](Request& req) {
    auto city = require_city(ctx, req);
    auto body = city_summary(city->info);
    nlohmann::json lines = nlohmann::json::array();
    for (const auto& l : city->metro.lines) lines.push_back(line_json(l));
    body["lines"] = std::move(lines);
    std::set<std::string> categories;
    for (const auto& p : city->pois)
      if (!p.category.empty()) categories.insert(p.category);
    body["poi_categories"] = categories;
    // With counts, for choosing interests (GET .../layout?interests=): derived once per city
    // version with the metro data (metro::CityMetroInput::categories), by id.
    nlohmann::json counted = nlohmann::json::array();
    for (const auto& c : ctx.metro.data_for(city->info.id)->categories.list)
      counted.push_back({{"id", c.id}, {"count", c.count}});
    body["categories"] = std::move(counted);
    const auto roads = covering_road_network(ctx.catalog, *city);
    body["road_network"] = roads.empty() ? nlohmann::json(nullptr) : nlohmann::json(roads);
    return cacheable(json_response(body));
  });

  router.add("GET", "/api/v1/cities/{id}/metro", Exec::light, [&ctx](Request& req) {
    auto bbox = query_bbox(req);
    auto city = require_city(ctx, req);
    return cacheable(geojson_response(metro_geojson(*city, bbox)));
  });

  router.add("GET", "/api/v1/cities/{id}/pois", Exec::light, [&ctx](Request& req) {
    auto bbox = query_bbox(req);
    PoiPage page;
    page.limit = static_cast<std::size_t>(query_int(req, "limit", 1, kMaxPoiLimit, kDefaultPoiLimit));
    page.offset = static_cast<std::size_t>(query_int(req, "offset", 0, 1'000'000'000, 0));
    auto city = require_city(ctx, req);
    return cacheable(geojson_response(pois_geojson(*city, bbox, all_pois(*city), page)));
  });

  // POIs inside a drawn area, optionally filtered by category: for mobile apps and the client.
  router.add("POST", "/api/v1/cities/{id}/pois/query", Exec::light, [&ctx](Request& req) {
    auto body = parse_json_body(req);
    if (!body.is_object()) throw bad("body", "expected a JSON object");
    reject_unknown(body, "", {"bbox", "within", "categories", "limit", "offset"});
    std::optional<geo::BBox> bbox;
    if (const auto* v = member(body, "bbox")) bbox = parse_bbox_json(*v, "bbox");
    std::optional<geo::PolygonSet> within;
    if (const auto* v = member(body, "within")) within.emplace(parse_polygons(*v, "within"));
    std::set<std::string> categories;
    if (const auto* v = member(body, "categories")) {
      const auto& list = json_array(*v, "categories", 0, kMaxQueryCategories);
      for (std::size_t i = 0; i < list.size(); ++i)
        categories.insert(json_string(list[i], "categories[" + std::to_string(i) + "]", kMaxCategoryBytes));
    }
    PoiPage page;
    if (const auto* v = member(body, "limit"))
      page.limit = static_cast<std::size_t>(json_integer(*v, "limit", 1, static_cast<long long>(kMaxPoiLimit)));
    if (const auto* v = member(body, "offset"))
      page.offset = static_cast<std::size_t>(json_integer(*v, "offset", 0, 1'000'000'000));

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
