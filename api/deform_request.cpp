#include "deform_request.hpp"

#include "geojson_in.hpp"
#include "params.hpp"

#include "geo/polygon.hpp"

#include <cmath>
#include <set>

namespace tourmap::api {
namespace {

std::int64_t node_id(const nlohmann::json& v, const std::string& field) {
  if (!v.is_number_integer()) throw bad(field, "expected a road node id (integer)");
  return v.get<std::int64_t>();
}

GridChoice parse_grid(const nlohmann::json& g, const DeformLimits& limits) {
  if (!g.is_object()) throw bad("grid", "expected an object like {\"kind\": \"adaptive\", \"base\": 10, \"depth\": 3}");
  GridChoice c;
  auto kind = member(g, "kind") ? json_choice(g["kind"], "grid.kind", {"adaptive", "uniform", "edges"}) : "adaptive";
  if (kind == "adaptive") {
    reject_unknown(g, "grid", {"kind", "base", "depth", "c"});
    c.kind = GridChoice::Kind::adaptive;
    if (auto* v = member(g, "base")) c.base = json_integer(*v, "grid.base", 1, limits.max_base);
    if (auto* v = member(g, "depth")) c.depth = json_integer(*v, "grid.depth", 0, limits.max_depth);
    if (auto* v = member(g, "c")) c.c = json_integer(*v, "grid.c", 0, 1000000);
  } else if (kind == "uniform") {
    reject_unknown(g, "grid", {"kind", "n"});
    c.kind = GridChoice::Kind::uniform;
    if (auto* v = member(g, "n")) c.n = json_integer(*v, "grid.n", 1, limits.max_uniform);
  } else {
    reject_unknown(g, "grid", {"kind"});
    c.kind = GridChoice::Kind::edges;
  }
  return c;
}

void parse_weights(const nlohmann::json& w, deform::Weights& out) {
  if (!w.is_object()) throw bad("weights", "expected an object");
  reject_unknown(w, "weights", {"road", "quad", "smooth", "guide"});
  if (auto* v = member(w, "road")) out.road = json_number(*v, "weights.road", 1e-6, 1e6);
  if (auto* v = member(w, "quad")) out.quad = json_number(*v, "weights.quad", 0, 1e6);
  if (auto* v = member(w, "smooth")) out.smooth = json_number(*v, "weights.smooth", 0, 1e6);
  if (auto* v = member(w, "guide")) out.guide = json_number(*v, "weights.guide", 1e-6, 1e9);
}

void parse_output(const nlohmann::json& o, DeformRequest& r) {
  if (!o.is_object()) throw bad("output", "expected an object");
  reject_unknown(o, "output", {"roads", "grid"});
  if (auto* v = member(o, "roads")) {
    auto s = json_choice(*v, "output.roads", {"geojson", "positions", "none"});
    r.roads_output = s == "geojson"     ? DeformRequest::RoadsOutput::geojson
                     : s == "positions" ? DeformRequest::RoadsOutput::positions
                                        : DeformRequest::RoadsOutput::none;
  }
  if (auto* v = member(o, "grid")) r.grid_output = json_bool(*v, "output.grid");
}

FocusRegionInput parse_region(const nlohmann::json& v, const std::string& field, const DeformLimits& limits) {
  if (!v.is_object()) throw bad(field, "expected {\"center\", \"radius_m\", \"scale\"} or {\"polygon\", \"scale\"}");
  reject_unknown(v, field, {"center", "radius_m", "polygon", "scale"});
  FocusRegionInput r;
  if (!member(v, "scale")) throw bad(field + ".scale", "missing (the focus scale factor Z)");
  const auto& s = v["scale"];
  if (!s.is_number()) throw bad(field + ".scale", "expected a number");
  r.scale = s.get<double>();
  // Z shrinks (Z < 1) or enlarges (Z > 1) a region; beyond 1/50..50 the map cannot give way.
  if (!std::isfinite(r.scale) || r.scale < 1.0 / limits.max_scale || r.scale > limits.max_scale)
    throw bad(field + ".scale", "must be between " + nlohmann::json(1.0 / limits.max_scale).dump() + " and " +
                                    nlohmann::json(limits.max_scale).dump());
  bool has_circle = member(v, "center") || member(v, "radius_m");
  bool has_polygon = member(v, "polygon") != nullptr;
  if (has_circle == has_polygon) throw bad(field, "give either center and radius_m, or polygon");
  if (has_polygon) {
    const auto& ring = json_array(v["polygon"], field + ".polygon", 3, limits.max_polygon_vertices);
    for (std::size_t i = 0; i < ring.size(); ++i)
      r.polygon.push_back(parse_position(ring[i], field + ".polygon[" + std::to_string(i) + "]"));
    // A closed ring may repeat its first position; an open one is closed implicitly.
    if (r.polygon.size() > 3 && r.polygon.front().lon == r.polygon.back().lon &&
        r.polygon.front().lat == r.polygon.back().lat)
      r.polygon.pop_back();
    if (!geo::is_simple_ring(r.polygon)) throw bad(field + ".polygon", "the polygon intersects itself or has zero area");
  } else {
    if (!member(v, "center")) throw bad(field + ".center", "missing");
    if (!member(v, "radius_m")) throw bad(field + ".radius_m", "missing");
    r.center = parse_position(v["center"], field + ".center");
    r.radius_m = json_number(v["radius_m"], field + ".radius_m", 1e-3, 1e7);
  }
  return r;
}

}  // namespace

const char* app_name(DeformApp app) {
  switch (app) {
    case DeformApp::focus: return "focus";
    case DeformApp::mental: return "mental";
    case DeformApp::destination: return "destination";
  }
  return "?";
}

std::string GridChoice::describe() const {
  switch (kind) {
    case Kind::adaptive:
      return "adaptive base=" + std::to_string(base) + " depth=" + std::to_string(depth) + " c=" + std::to_string(c);
    case Kind::uniform: return "uniform n=" + std::to_string(n);
    case Kind::edges: return "edges";
  }
  return "?";
}

DeformRequest parse_deform_request(DeformApp app, const nlohmann::json& body, const DeformLimits& limits) {
  if (!body.is_object()) throw bad("body", "expected a JSON object");
  DeformRequest r;
  r.app = app;
  r.canonical = body.dump();
  std::vector<const char*> common = {"roads", "grid", "solver", "weights", "boundary", "cg", "time_limit_ms",
                                     "relax", "check_crossings", "output", "map_points"};
  std::vector<const char*> specific;
  if (app == DeformApp::focus) specific = {"regions"};
  if (app == DeformApp::mental) specific = {"guides"};
  if (app == DeformApp::destination) specific = {"route", "sketch", "simplify_m"};
  for (auto it = body.begin(); it != body.end(); ++it) {
    bool ok = false;
    for (auto k : common) ok = ok || it.key() == k;
    for (auto k : specific) ok = ok || it.key() == k;
    if (!ok) throw bad(shown(it.key()), std::string("unknown field for /deform/") + app_name(app));
  }

  const auto* roads = member(body, "roads");
  if (!roads) throw bad("roads", "missing (a road network id, or a GeoJSON FeatureCollection of LineStrings)");
  if (roads->is_string()) {
    r.roads_id = roads->get<std::string>();
  } else if (roads->is_object()) {
    r.roads_inline = *roads;
  } else {
    throw bad("roads", "expected a road network id or a GeoJSON FeatureCollection");
  }

  if (auto* v = member(body, "grid")) r.grid = parse_grid(*v, limits);
  if (auto* v = member(body, "solver")) {
    r.solver = json_choice(*v, "solver", {"cholesky", "cg"}) == "cg" ? deform::SolverKind::cg : deform::SolverKind::cholesky;
  }
  if (auto* v = member(body, "weights")) parse_weights(*v, r.weights);
  if (auto* v = member(body, "boundary"))
    r.boundary = json_choice(*v, "boundary", {"fixed", "sliding"}) == "sliding" ? deform::Boundary::sliding
                                                                          : deform::Boundary::fixed;
  if (auto* v = member(body, "cg")) {
    if (!v->is_object()) throw bad("cg", "expected an object");
    reject_unknown(*v, "cg", {"max_iterations", "tolerance"});
    if (auto* m = member(*v, "max_iterations")) r.max_iterations = json_integer(*m, "cg.max_iterations", 1, 1000000);
    if (auto* t = member(*v, "tolerance")) r.tolerance = json_number(*t, "cg.tolerance", 1e-14, 1e-1);
  }
  if (auto* v = member(body, "time_limit_ms")) r.time_limit_ms = json_number(*v, "time_limit_ms", 1, limits.max_time_limit_ms);
  if (auto* v = member(body, "relax")) r.relax = json_bool(*v, "relax");
  if (auto* v = member(body, "check_crossings")) r.check_crossings = json_bool(*v, "check_crossings");
  if (auto* v = member(body, "output")) parse_output(*v, r);
  if (auto* v = member(body, "map_points")) {
    const auto& pts = json_array(*v, "map_points", 0, limits.max_map_points);
    for (std::size_t i = 0; i < pts.size(); ++i)
      r.map_points.push_back(parse_position(pts[i], "map_points[" + std::to_string(i) + "]"));
  }

  if (app == DeformApp::focus) {
    const auto* regions = member(body, "regions");
    if (!regions) throw bad("regions", "missing (at least one focus region)");
    const auto& list = json_array(*regions, "regions", 1, limits.max_regions);
    // One vertex budget for all polygons: each road edge is tested against every region.
    std::size_t vertices = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
      r.regions.push_back(parse_region(list[i], "regions[" + std::to_string(i) + "]", limits));
      vertices += r.regions.back().polygon.size();
      if (vertices > limits.max_polygon_vertices)
        throw too_large("regions",
                        "at most " + std::to_string(limits.max_polygon_vertices) + " polygon vertices in all regions together");
    }
  }
  if (app == DeformApp::mental) {
    const auto* guides = member(body, "guides");
    if (!guides) throw bad("guides", "missing (road vertices and their target points)");
    const auto& list = json_array(*guides, "guides", 1, limits.max_guides);
    for (std::size_t i = 0; i < list.size(); ++i) {
      auto field = "guides[" + std::to_string(i) + "]";
      const auto& g = list[i];
      if (!g.is_object()) throw bad(field, "expected {\"vertex\" or \"point\", \"target\"}");
      reject_unknown(g, field, {"vertex", "point", "target"});
      GuideInput in;
      if (member(g, "vertex") && member(g, "point")) throw bad(field, "give vertex or point, not both");
      if (auto* v = member(g, "vertex")) in.vertex = node_id(*v, field + ".vertex");
      else if (auto* p = member(g, "point")) in.point = parse_position(*p, field + ".point");
      else throw bad(field + ".vertex", "missing (or give a point to snap to the nearest road vertex)");
      if (!member(g, "target")) throw bad(field + ".target", "missing");
      in.target = parse_position(g["target"], field + ".target");
      r.guides.push_back(in);
    }
  }
  if (app == DeformApp::destination) {
    const auto* route = member(body, "route");
    if (!route) throw bad("route", "missing (road node ids along the route)");
    const auto& ids = json_array(*route, "route", 2, limits.max_route);
    for (std::size_t i = 0; i < ids.size(); ++i) r.route.push_back(node_id(ids[i], "route[" + std::to_string(i) + "]"));
    const auto* sketch = member(body, "sketch");
    if (!sketch) throw bad("sketch", "missing (the sketch polyline, at least 2 points)");
    const auto& pts = json_array(*sketch, "sketch", 2, limits.max_polygon_vertices);
    for (std::size_t i = 0; i < pts.size(); ++i)
      r.sketch.push_back(parse_position(pts[i], "sketch[" + std::to_string(i) + "]"));
    if (auto* v = member(body, "simplify_m")) r.simplify_m = json_number(*v, "simplify_m", 0, 1e6);
  }
  return r;
}

}  // namespace tourmap::api
