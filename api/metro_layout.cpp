#include "metro_layout.hpp"

#include "geojson.hpp"
#include "params.hpp"

#include "metro/octilinear_grid.hpp"
#include "metro/octilinear_mip.hpp"
#include "metro/prelayout.hpp"
#include "metro/warp.hpp"
#include "util/elapsed.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include <chrono>
#include <cmath>
#include <cstdio>

namespace tourmap::api {
namespace {

constexpr int kLayoutVersion = 4;
using util::Clock;
using util::ms_since;

double round1(double v) { return std::round(v * 10) / 10; }
nlohmann::json xy(geo::XY p) { return nlohmann::json::array({round1(p.x), round1(p.y)}); }

RankSource rank_from(const std::string& s, const std::string& field) {
  if (s == "auto") return RankSource::automatic;
  if (s == "data") return RankSource::data;
  if (s == "proxy") return RankSource::proxy;
  if (s == "uniform") return RankSource::uniform;
  throw bad(field, "expected auto, data, proxy or uniform");
}

LayoutRequest::Solver solver_from(const std::string& s) {
  if (s == "auto") return LayoutRequest::Solver::automatic;
  if (s == "fast") return LayoutRequest::Solver::fast;
  if (s == "mip") return LayoutRequest::Solver::mip;
  throw bad("solver", "expected auto, mip or fast");
}

double bounded(double v, const std::string& field, double lo, double hi) {
  if (!std::isfinite(v) || v < lo || v > hi)
    throw bad(field, "must be between " + nlohmann::json(lo).dump() + " and " + nlohmann::json(hi).dump());
  return v;
}

void set_number(LayoutRequest& r, const std::string& key, double v) {
  if (key == "time_limit_s") r.time_limit_s = bounded(v, key, 0.1, 60);
  else if (key == "w_r") r.worth.w_rank = bounded(v, key, 0, 10);
  else if (key == "w_rho") r.worth.w_proximity = bounded(v, key, 0, 10);
  else if (key == "k") r.worth.k_m = bounded(v, key, 10, 100000);
  else if (key == "l_const") r.l_const = bounded(v, key, 1, 1000);
}

// Uniform scale + translation taking `from` onto `to` in the least-squares sense.
std::pair<double, geo::XY> fit_scale_translation(const std::vector<geo::XY>& from, const std::vector<geo::XY>& to) {
  std::size_t n = from.size();
  geo::XY cf{0, 0}, ct{0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    cf.x += from[i].x / n;
    cf.y += from[i].y / n;
    ct.x += to[i].x / n;
    ct.y += to[i].y / n;
  }
  double num = 0, den = 0;
  for (std::size_t i = 0; i < n; ++i) {
    num += (from[i].x - cf.x) * (to[i].x - ct.x) + (from[i].y - cf.y) * (to[i].y - ct.y);
    den += (from[i].x - cf.x) * (from[i].x - cf.x) + (from[i].y - cf.y) * (from[i].y - cf.y);
  }
  double s = den > 0 ? num / den : 1.0;
  return {s, {ct.x - s * cf.x, ct.y - s * cf.y}};
}

nlohmann::json quality_json(const metro::LayoutQuality& q) {
  return {{"octilinear_share", q.octilinear_share}, {"bends", q.bends},
          {"crossings", q.crossings},               {"geo_crossings", q.geo_crossings},
          {"added_crossings", q.added_crossings},
          {"order_violations", q.order_violations}, {"min_edge", q.min_edge},
          {"mean_edge", q.mean_edge},               {"mean_displacement", q.mean_displacement}};
}

}  // namespace

std::string LayoutRequest::canonical() const {
  char buf[256];
  // v: the layout algorithm's version; bump it when results change, so stored layouts renew.
  std::snprintf(buf, sizeof buf, "v=%d lengths=%s solver=%d t=%.3f rank=%d wr=%.6g wrho=%.6g k=%.6g l=%.6g",
                kLayoutVersion, worth_lengths ? "vw" : "uniform", static_cast<int>(solver), time_limit_s, static_cast<int>(rank),
                worth.w_rank, worth.w_proximity, worth.k_m, l_const);
  return buf;
}

LayoutRequest parse_layout_query(const Request& req) {
  LayoutRequest r;
  for (const auto& [key, value] : req.query) {
    if (key == "lengths") {
      if (value != "visual-worth" && value != "uniform") throw bad(key, "expected visual-worth or uniform");
      r.worth_lengths = value == "visual-worth";
    } else if (key == "solver") {
      r.solver = solver_from(value);
    } else if (key == "rank") {
      r.rank = rank_from(value, key);
    } else if (key == "time_limit_s" || key == "w_r" || key == "w_rho" || key == "k" || key == "l_const") {
      char* end = nullptr;
      double v = std::strtod(value.c_str(), &end);
      if (value.empty() || end != value.c_str() + value.size()) throw bad(key, "'" + value + "' is not a number");
      set_number(r, key, v);
    }
  }
  return r;
}

LayoutRequest parse_layout_body(const nlohmann::json& body) {
  if (!body.is_object()) throw bad("body", "expected a JSON object");
  LayoutRequest r;
  for (auto it = body.begin(); it != body.end(); ++it) {
    const auto& key = it.key();
    const auto& v = it.value();
    if (key == "lengths" || key == "solver" || key == "rank") {
      if (!v.is_string()) throw bad(key, "expected a string");
      auto s = v.get<std::string>();
      if (key == "lengths") {
        if (s != "visual-worth" && s != "uniform") throw bad(key, "expected visual-worth or uniform");
        r.worth_lengths = s == "visual-worth";
      } else if (key == "solver") {
        r.solver = solver_from(s);
      } else {
        r.rank = rank_from(s, key);
      }
    } else if (key == "time_limit_s" || key == "w_r" || key == "w_rho" || key == "k" || key == "l_const") {
      if (!v.is_number()) throw bad(key, "expected a number");
      set_number(r, key, v.get<double>());
    } else {
      throw bad(key, "unknown field");
    }
  }
  return r;
}

std::vector<double> poi_worth_geo(const CityMetroData& data, RankSource rank, const metro::WorthParams& params) {
  auto vw = make_visual_worth(data, rank, params);
  return vw.at_points(data.poi_xy);  // batched: exact within the work budget, else bounded
}

std::shared_ptr<const CityLayout> compute_city_layout(const CityMetroData& d, const LayoutRequest& req,
                                                      const MipSolver& mip) {
  auto started = Clock::now();
  auto result = std::make_shared<CityLayout>();
  const auto& city = *d.city;
  const auto& net = city.metro;

  // 1. Visual worth (5.4.1) at every node and POI.
  auto t = Clock::now();
  auto vw = make_visual_worth(d, req.rank, req.worth);
  std::vector<geo::XY> worth_points(d.graph.pos);  // nodes, then POIs: one batched evaluation
  worth_points.insert(worth_points.end(), d.poi_xy.begin(), d.poi_xy.end());
  auto worth = vw.at_points(worth_points);
  const auto nodes_end = worth.begin() + static_cast<std::ptrdiff_t>(d.graph.pos.size());
  std::vector<double> node_worth(worth.begin(), nodes_end);
  result->poi_worth.assign(nodes_end, worth.end());
  double vw_ms = ms_since(t);

  // 2. Octilinear layout (5.4.2) with edge lengths from visual worth (eq. 5.3, 5.4) or uniform.
  t = Clock::now();
  auto g = d.graph;
  g.min_length = req.worth_lengths ? metro::visual_worth_lengths(g, node_worth, req.l_const)
                                   : std::vector<double>(g.edges.size(), req.l_const);
  auto start = metro::stress_layout(g, metro::scale_to_lengths(g));
  const double prelayout_ms = ms_since(t);
  metro::GridRouteParams params;
  params.time_limit_ms = req.time_limit_s * 1000.0;
  metro::GridRouteReport report;
  auto layout = metro::route_octilinear(g, start, params, &report);
  result->quality = metro::measure_layout(g, layout);
  result->status = layout.status;
  double fast_ms = ms_since(t);

  // Optional MIP polish (see the header for the policy).
  nlohmann::json solver = {{"kind", "fast"}, {"status", layout.status}, {"gap", nullptr}};
  std::size_t station_count = d.city->info.station_count;
  bool want_mip = req.solver == LayoutRequest::Solver::mip ||
                  (req.solver == LayoutRequest::Solver::automatic && station_count <= kAutoMipStations);
  double left_s = req.time_limit_s - fast_ms / 1000.0;
  double budget = req.solver == LayoutRequest::Solver::mip ? left_s : std::min(0.5, 0.1 * req.time_limit_s);
  budget = std::min(budget, left_s);
  if (want_mip && budget < 0.2) {
    solver["mip"] = {{"status", "skipped"}, {"reason", "no time left"}};
  } else if (want_mip) {
    auto t_mip = Clock::now();
    auto model = metro::build_octilinear_mip(g, layout, {1.0, 50.0, 1.0, req.l_const});
    const double build_ms = ms_since(t_mip);
    if (model.model.columns() > kMaxMipColumns) {
      solver["mip"] = {{"status", "skipped"}, {"reason", "network too large for the MIP"}};
    } else {
      auto r = mip(model.model, budget, 0.01);
      nlohmann::json info = {{"status", r.status}, {"columns", model.model.columns()},
                             {"rows", model.model.rows.size()}, {"start_objective", model.start_objective},
                             {"build_ms", build_ms}, {"time_ms", ms_since(t_mip)}};
      if (!r.x.empty()) {
        auto polished = metro::decode_octilinear_mip(model, r.x, g.pos.size());
        auto q = metro::measure_layout(g, polished);
        info["objective"] = r.objective;
        info["gap"] = r.gap;
        bool better = r.objective < model.start_objective - 1e-6;
        bool no_worse = q.octilinear_share >= result->quality.octilinear_share && q.crossings <= result->quality.crossings &&
                        q.added_crossings <= result->quality.added_crossings &&
                        q.order_violations <= result->quality.order_violations;
        if (better && no_worse) {
          polished.status = r.status;
          layout = std::move(polished);
          result->quality = q;
          result->status = layout.status;
          solver = {{"kind", "mip"}, {"status", r.status}, {"gap", r.gap}};
          info["accepted"] = true;
        } else {
          info["accepted"] = false;
          std::string why = "no improvement on the start";
          if (better) {
            why = "it would have " + std::to_string(q.crossings) + " crossings (" + std::to_string(q.added_crossings) +
                  " added) and " + std::to_string(q.order_violations) + " order violations, the fast layout " +
                  std::to_string(result->quality.crossings) + " (" + std::to_string(result->quality.added_crossings) +
                  ") and " + std::to_string(result->quality.order_violations);
          }
          info["reason"] = why;
        }
      }
      solver["mip"] = std::move(info);
    }
  }
  double layout_ms = ms_since(t);

  // 3. Into the geographic frame, and warping (5.4.3) of POIs, outline and mesh.
  t = Clock::now();
  auto [scale, shift] = fit_scale_translation(layout.pos, g.pos);
  auto frame = [&, s = scale, sh = shift](geo::XY p) { return geo::XY{s * p.x + sh.x, s * p.y + sh.y}; };
  std::vector<geo::XY> stations_layout;
  for (const auto& p : layout.pos) stations_layout.push_back(frame(p));
  metro::Warp warp(g.pos, stations_layout);
  geo::BBox extent;
  for (const auto& p : g.pos) extent.extend({p.x, p.y});
  double diag = std::hypot(extent.max_lon - extent.min_lon, extent.max_lat - extent.min_lat);
  double reach = std::max(2000.0, 0.25 * diag);
  for (const auto& p : d.poi_xy) {
    result->poi_layout.push_back(warp(p));
    double dx = std::max({extent.min_lon - p.x, 0.0, p.x - extent.max_lon});
    double dy = std::max({extent.min_lat - p.y, 0.0, p.y - extent.max_lat});
    result->poi_outside.push_back(std::hypot(dx, dy) > reach);
  }
  const int mesh_n = 20;
  double pad = 0.1 * diag;
  nlohmann::json mesh_geo = nlohmann::json::array(), mesh_layout = nlohmann::json::array();
  for (int j = 0; j <= mesh_n; ++j)
    for (int i = 0; i <= mesh_n; ++i) {
      geo::XY p{extent.min_lon - pad + (extent.max_lon - extent.min_lon + 2 * pad) * i / mesh_n,
                extent.min_lat - pad + (extent.max_lat - extent.min_lat + 2 * pad) * j / mesh_n};
      mesh_geo.push_back(xy(p));
      mesh_layout.push_back(xy(warp(p)));
    }
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<Kernel::Point_2> pts, hull;
  for (const auto& p : g.pos) pts.emplace_back(p.x, p.y);
  CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull));
  nlohmann::json outline_geo = nlohmann::json::array(), outline_layout = nlohmann::json::array();
  for (const auto& p : hull) {
    outline_geo.push_back(xy({p.x(), p.y()}));
    outline_layout.push_back(xy(warp({p.x(), p.y()})));
  }
  double warp_ms = ms_since(t);

  // 4. The answer.
  double max_worth = 0;
  for (std::size_t v = 0; v < node_worth.size(); ++v)
    if (net.nodes[v].is_station()) max_worth = std::max(max_worth, node_worth[v]);
  auto line_ids = [&](const std::vector<std::uint32_t>& idx) {
    nlohmann::json ids = nlohmann::json::array();
    for (auto l : idx) ids.push_back(net.lines[l].id);
    return ids;
  };
  std::vector<std::vector<std::uint32_t>> node_lines(net.nodes.size());
  for (const auto& e : net.edges)
    for (auto l : e.lines)
      for (auto v : {e.from, e.to})
        if (std::find(node_lines[v].begin(), node_lines[v].end(), l) == node_lines[v].end()) node_lines[v].push_back(l);
  nlohmann::json stations = nlohmann::json::array();
  for (std::size_t v = 0; v < net.nodes.size(); ++v) {
    const auto& n = net.nodes[v];
    if (!n.is_station()) continue;
    stations.push_back({{"type", "Feature"},
                        {"id", n.id},
                        {"geometry", {{"type", "Point"}, {"coordinates", xy(stations_layout[v])}}},
                        {"properties", {{"id", n.id},
                                        {"station_id", n.station_id},
                                        {"name", n.name},
                                        {"lines", line_ids(node_lines[v])},
                                        {"worth", max_worth > 0 ? node_worth[v] / max_worth : 0.0},
                                        {"geo", xy(g.pos[v])},
                                        {"lonlat", position(n.pos)}}}});
  }
  nlohmann::json edges = nlohmann::json::array();
  for (std::size_t e = 0; e < net.edges.size(); ++e) {
    nlohmann::json coords = nlohmann::json::array(), geo_coords = nlohmann::json::array();
    for (const auto& p : layout.paths[e]) coords.push_back(xy(frame(p)));
    for (const auto& p : net.edges[e].geometry) geo_coords.push_back(xy(geo::project(d.projection, p)));
    edges.push_back({{"type", "Feature"},
                     {"geometry", {{"type", "LineString"}, {"coordinates", std::move(coords)}}},
                     {"properties", {{"from", net.nodes[net.edges[e].from].id},
                                     {"to", net.nodes[net.edges[e].to].id},
                                     {"lines", line_ids(net.edges[e].lines)},
                                     {"min_length", round1(scale * g.min_length[e])},
                                     {"geo", std::move(geo_coords)}}}});
  }
  double max_poi_worth = 0;
  for (double w : result->poi_worth) max_poi_worth = std::max(max_poi_worth, w);
  nlohmann::json pois = nlohmann::json::array();
  for (std::size_t i = 0; i < city.pois.size(); ++i) {
    const auto& p = city.pois[i];
    nlohmann::json props = {{"id", p.id},
                            {"name", p.name},
                            {"category", p.category},
                            {"worth", max_poi_worth > 0 ? result->poi_worth[i] / max_poi_worth : 0.0},
                            {"station_km", std::round(d.poi_station_km[i] * 1000) / 1000},
                            {"outside", static_cast<bool>(result->poi_outside[i])},
                            {"geo", xy(d.poi_xy[i])},
                            {"lonlat", position(p.pos)}};
    if (!p.image_url.empty()) props["image"] = p.image_url;
    if (!p.url.empty()) props["url"] = p.url;
    if (!p.wikipedia.empty()) props["wikipedia"] = p.wikipedia;
    pois.push_back({{"type", "Feature"},
                    {"id", p.id},
                    {"geometry", {{"type", "Point"}, {"coordinates", xy(result->poi_layout[i])}}},
                    {"properties", std::move(props)}});
  }
  nlohmann::json lines = nlohmann::json::array();
  for (const auto& l : net.lines) lines.push_back({{"id", l.id}, {"label", l.label}, {"color", l.color}});
  nlohmann::json attribution = nlohmann::json::array();
  if (!city.info.attribution.empty()) attribution.push_back(city.info.attribution);
  if (!city.info.poi_attribution.empty()) attribution.push_back(city.info.poi_attribution);

  nlohmann::json body = {
      {"city", city.info.id},
      {"version", city.info.version},
      {"frame", {{"kind", "city-metres"},
                 {"description", "x east, y north, metres in the city's transverse Mercator projection; the layout "
                                 "is aligned to the geography by a uniform scale and a translation"},
                 {"projection", {{"kind", "transverse_mercator"},
                                 {"lon0", d.projection.origin.lon},
                                 {"lat0", d.projection.origin.lat},
                                 {"k0", 1.0}}},
                 {"layout_units_per_metre", scale != 0 ? 1.0 / scale : 0.0}}},
      {"params", {{"lengths", req.worth_lengths ? "visual-worth" : "uniform"},
                  {"rank", req.rank == RankSource::automatic ? (d.has_rank ? "data" : "proxy")
                           : req.rank == RankSource::data  ? "data"
                           : req.rank == RankSource::proxy ? "proxy"
                                                            : "uniform"},
                  {"w_r", req.worth.w_rank},
                  {"w_rho", req.worth.w_proximity},
                  {"k", req.worth.k_m},
                  {"l_const", req.l_const},
                  {"time_limit_s", req.time_limit_s}}},
      {"stations", {{"type", "FeatureCollection"}, {"features", std::move(stations)}}},
      {"edges", {{"type", "FeatureCollection"}, {"features", std::move(edges)}}},
      {"pois", {{"type", "FeatureCollection"}, {"features", std::move(pois)}}},
      {"mesh", {{"cols", mesh_n + 1}, {"rows", mesh_n + 1}, {"geo", std::move(mesh_geo)}, {"layout", std::move(mesh_layout)}}},
      {"outline", {{"geo", std::move(outline_geo)}, {"layout", std::move(outline_layout)}}},
      {"lines", std::move(lines)},
      {"quality", quality_json(result->quality)},
      {"solver", std::move(solver)},
      {"fast_path", {{"status", report.timed_out ? "time_limit" : report.failed ? "incomplete" : report.overlapping ? "overlapping" : "ok"},
                     {"time_ms", fast_ms},
                     {"prelayout_ms", prelayout_ms},
                     {"chains", report.chains},
                     {"contracted_nodes", report.contracted_nodes},
                     {"ripups", report.ripups},
                     {"overlapping", report.overlapping},
                     {"crossing_routes", report.crossing_routes},
                     {"failed", report.failed},
                     {"attempt", report.attempt}}},
      {"timing_ms", {{"visual_worth", vw_ms}, {"layout", layout_ms}, {"warp", warp_ms}, {"total", ms_since(started)}}},
      {"attribution", std::move(attribution)}};
  result->body = body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return result;
}

}  // namespace tourmap::api
