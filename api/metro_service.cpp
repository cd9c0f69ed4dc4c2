#include "metro_service.hpp"

#include "geojson.hpp"
#include "params.hpp"

#include "poi/active_clusters.hpp"
#include "poi/serialize.hpp"
#include "store/repo.hpp"

#include <chrono>
#include <cmath>

namespace tourmap::api {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

ApiError bad(const std::string& field, const std::string& message) {
  return ApiError(400, "invalid_parameter", field + ": " + message, field);
}

// A layout read back from the store: the positions the clusters need come from its JSON.
std::shared_ptr<const CityLayout> layout_from_body(std::string body) {
  auto doc = nlohmann::json::parse(body);
  auto l = std::make_shared<CityLayout>();
  for (const auto& f : doc["pois"]["features"]) {
    l->poi_layout.push_back({f["geometry"]["coordinates"][0].get<double>(), f["geometry"]["coordinates"][1].get<double>()});
    l->poi_worth.push_back(f["properties"]["worth"].get<double>());
    l->poi_outside.push_back(f["properties"]["outside"].get<bool>());
  }
  l->status = doc["solver"]["status"].get<std::string>();
  l->body = std::move(body);
  return l;
}

}  // namespace

MetroService::MetroService(Catalog& catalog, MipSolver mip, MetroLimits limits)
    : catalog_(catalog), mip_(std::move(mip)), limits_(limits) {
  if (!mip_) mip_ = [](const metro::MipModel& m, double t, double gap) { return metro::solve_with_cbc(m, t, gap); };
}

std::shared_ptr<const CityMetroData> MetroService::data_for(const std::string& city_id) {
  require_slug(city_id, "city");
  auto city = catalog_.city(city_id);
  if (!city) throw ApiError(404, "not_found", "no city '" + city_id + "'", "id");
  auto key = city->info.id + "@" + std::to_string(city->info.version);
  if (auto hit = data_.get(key)) return *hit;
  auto d = make_city_metro_data(city);
  data_.put(key, d);
  return d;
}

std::shared_ptr<const CityLayout> MetroService::layout_for(const CityMetroData& data, const LayoutRequest& req,
                                                          bool* cached) {
  auto key = "layout:" + data.key + ":" + req.canonical();
  *cached = true;
  if (auto hit = layouts_.get(key)) return *hit;
  bool ran = false;
  auto layout = layout_flight_.run(
      key,
      [&]() -> std::shared_ptr<const CityLayout> {
        auto db = catalog_.pool().acquire();
        if (auto stored = store::cache_get(*db, key)) return layout_from_body(std::move(stored->body));
        auto computed = compute_city_layout(data, req, mip_);
        store::cache_put(*db, key, "layout", {"application/json", computed->body});
        *cached = false;
        return computed;
      },
      &ran);
  layouts_.put(key, layout);
  return layout;
}

std::shared_ptr<const poi::ClusterTree> MetroService::tree_for(const std::string& key,
                                                              const std::vector<geo::XY>& points,
                                                              const std::vector<double>& worth,
                                                              const std::vector<bool>* skip) {
  if (auto hit = trees_.get(key)) return *hit;
  auto tree = tree_flight_.run(key, [&]() -> std::shared_ptr<const poi::ClusterTree> {
    auto db = catalog_.pool().acquire();
    if (auto stored = store::cache_get(*db, key)) {
      try {
        return std::make_shared<const poi::ClusterTree>(poi::deserialize(stored->body));
      } catch (const std::invalid_argument&) {  // an older or damaged entry: rebuild it
      }
    }
    std::vector<poi::ClusterPoint> in;
    for (std::size_t i = 0; i < points.size(); ++i)
      in.push_back({points[i], skip && (*skip)[i] ? 0.0 : worth[i]});
    auto built = std::make_shared<const poi::ClusterTree>(poi::build_cluster_tree(in));
    store::cache_put(*db, key, "clusters", {"application/octet-stream", poi::serialize(*built)});
    return built;
  });
  trees_.put(key, tree);
  return tree;
}

Response MetroService::layout(const Request& req, bool post) {
  auto params = post ? parse_layout_body(parse_json_body(req)) : parse_layout_query(req);
  auto data = data_for(req.param("id"));
  if (data->graph.edges.empty()) throw ApiError(422, "empty_network", "city has no metro edges to lay out", "id");
  bool cached = false;
  auto layout = layout_for(*data, params, &cached);
  Response r;
  r.body = layout->body;
  r.cacheable = !post;
  r.headers.emplace_back("X-Result-Cache", cached ? "hit" : "miss");
  return r;
}

Response MetroService::visual_worth(const Request& req) {
  auto bbox = query_bbox(req);
  auto width = static_cast<std::size_t>(query_int(req, "width", 1, static_cast<long long>(limits_.max_raster_side), 128));
  auto height = static_cast<std::size_t>(query_int(req, "height", 1, static_cast<long long>(limits_.max_raster_side), 128));
  LayoutRequest params = parse_layout_query(req);  // rank, w_r, w_rho, k
  auto data = data_for(req.param("id"));
  auto started = Clock::now();
  auto vw = make_visual_worth(*data, params.rank, params.worth);
  geo::BBox box = bbox ? *bbox : data->city->info.bbox;
  std::vector<double> raw(width * height);
  double max = 0;
  for (std::size_t j = 0; j < height; ++j)
    for (std::size_t i = 0; i < width; ++i) {
      // Cell centres, rows from north to south (image order).
      geo::LonLat p{box.min_lon + (box.max_lon - box.min_lon) * (i + 0.5) / width,
                    box.max_lat - (box.max_lat - box.min_lat) * (j + 0.5) / height};
      double v = vw.at(geo::project(data->projection, p));
      raw[j * width + i] = v;
      max = std::max(max, v);
    }
  nlohmann::json values = nlohmann::json::array();
  for (double v : raw) values.push_back(max > 0 ? std::round(v / max * 1000) / 1000 : 0.0);
  nlohmann::json stations = nlohmann::json::array();
  const auto& nodes = data->city->metro.nodes;
  for (std::size_t v = 0; v < nodes.size(); ++v)
    if (nodes[v].is_station())
      stations.push_back({{"id", nodes[v].id}, {"worth", max > 0 ? vw.at(data->graph.pos[v]) / max : 0.0}});
  Response r = json_response({{"city", data->city->info.id},
                              {"bbox", bbox_json(box)},
                              {"width", width},
                              {"height", height},
                              {"values", std::move(values)},
                              {"max", max},
                              {"pois", vw.size()},
                              {"stations", std::move(stations)},
                              {"took_ms", ms_since(started)}});
  r.cacheable = true;
  return r;
}

Response MetroService::clusters(const Request& req) {
  auto started = Clock::now();
  std::string space = req.query_param("space") ? *req.query_param("space") : "geo";
  if (space != "geo" && space != "layout") throw bad("space", "expected geo or layout");
  auto m = static_cast<std::size_t>(query_int(req, "m", 1, static_cast<long long>(limits_.max_m), 10));
  auto data = data_for(req.param("id"));
  const auto& pois = data->city->pois;

  std::shared_ptr<const poi::ClusterTree> tree;
  geo::XY lo, hi;
  const auto* bbox_text = req.query_param("bbox");
  if (space == "geo") {
    auto box = bbox_text ? parse_bbox(*bbox_text, "bbox") : data->city->info.poi_bbox;
    auto a = geo::project(data->projection, {box.min_lon, box.min_lat});
    auto b = geo::project(data->projection, {box.max_lon, box.max_lat});
    auto c = geo::project(data->projection, {box.min_lon, box.max_lat});
    auto e = geo::project(data->projection, {box.max_lon, box.min_lat});
    lo = {std::min({a.x, b.x, c.x, e.x}), std::min({a.y, b.y, c.y, e.y})};
    hi = {std::max({a.x, b.x, c.x, e.x}), std::max({a.y, b.y, c.y, e.y})};
    auto worth_key = "worth:" + data->key;
    std::shared_ptr<const std::vector<double>> worth;
    if (auto hit = geo_worth_.get(worth_key)) {
      worth = *hit;
    } else {
      worth = std::make_shared<const std::vector<double>>(poi_worth_geo(*data, RankSource::automatic, {}));
      geo_worth_.put(worth_key, worth);
    }
    tree = tree_for("clusters:geo:" + data->key, data->poi_xy, *worth, nullptr);
  } else {
    // Layout space: the bbox is in the layout's frame (metres, see GET .../layout).
    if (!bbox_text) throw bad("bbox", "required for space=layout (x0,y0,x1,y1 in the layout frame)");
    std::vector<double> v;
    std::size_t start = 0;
    while (v.size() < 5) {
      auto comma = bbox_text->find(',', start);
      auto part = bbox_text->substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      char* end = nullptr;
      double x = std::strtod(part.c_str(), &end);
      if (part.empty() || end != part.c_str() + part.size() || !std::isfinite(x)) throw bad("bbox", "expected 4 finite numbers");
      v.push_back(x);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    if (v.size() != 4) throw bad("bbox", "expected 4 numbers x0,y0,x1,y1");
    if (v[0] > v[2] || v[1] > v[3]) throw bad("bbox", "min must not exceed max");
    lo = {v[0], v[1]};
    hi = {v[2], v[3]};
    auto params = parse_layout_query(req);
    bool cached = false;
    auto layout = layout_for(*data, params, &cached);
    tree = tree_for("clusters:layout:" + data->key + ":" + params.canonical(), layout->poi_layout, layout->poi_worth,
                    &layout->poi_outside);
  }

  // At least 2M active clusters where the tree allows, so a whole-map window fills the top M
  // and the M previews (see poi/active_clusters.hpp).
  auto active = poi::active_clusters(*tree, lo, hi, m, 2 * m);
  auto describe = [&](std::uint32_t node, double prominence) {
    const auto& c = tree->nodes[node];
    const auto& rep = pois[c.representative];
    nlohmann::json center = space == "geo" ? position(geo::unproject(data->projection, c.center))
                                           : nlohmann::json::array({std::round(c.center.x * 10) / 10, std::round(c.center.y * 10) / 10});
    nlohmann::json representative = {{"id", rep.id}, {"name", rep.name}, {"category", rep.category}};
    if (!rep.image_url.empty()) representative["image"] = rep.image_url;
    if (!rep.url.empty()) representative["url"] = rep.url;
    if (!rep.wikipedia.empty()) representative["wikipedia"] = rep.wikipedia;
    // Leaves are the POIs in input order, so the representative's leaf holds its position in
    // the tree's space (its warped position for space=layout).
    const geo::XY at = tree->nodes[c.representative].center;
    representative["position"] = space == "geo" ? position(rep.pos)
                                                : nlohmann::json::array({std::round(at.x * 10) / 10, std::round(at.y * 10) / 10});
    return nlohmann::json{{"id", std::string("c").append(std::to_string(node))},
                          {"center", std::move(center)},
                          {"size", c.size},
                          {"prominence", prominence},
                          {"representative", std::move(representative)}};
  };
  nlohmann::json top = nlohmann::json::array(), previews = nlohmann::json::array();
  for (std::size_t i = 0; i < active.top.size(); ++i) top.push_back(describe(active.top[i], active.prominence[i]));
  for (std::size_t i = 0; i < active.previews.size(); ++i)
    previews.push_back(describe(active.previews[i], active.prominence[active.top.size() + i]));
  Response r = json_response({{"city", data->city->info.id},
                              {"space", space},
                              {"active", active.active},
                              {"clusters", std::move(top)},
                              {"previews", std::move(previews)},
                              {"took_ms", ms_since(started)}});
  r.cacheable = true;
  return r;
}

}  // namespace tourmap::api
