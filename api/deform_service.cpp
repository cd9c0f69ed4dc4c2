#include "deform_service.hpp"

#include "geojson.hpp"
#include "positions_binary.hpp"
#include "json_out.hpp"
#include "params.hpp"
#include "roads_in.hpp"

#include "grid/grid.hpp"
#include "util/elapsed.hpp"
#include "util/hash.hpp"

#include <chrono>
#include <cstdio>

namespace tourmap::api {
namespace {

using util::Clock;
using util::ms_since;

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}


std::shared_ptr<DeformNetwork> make_network(std::string key, std::shared_ptr<const RoadNetworkEntry> entry) {
  auto n = std::make_shared<DeformNetwork>();
  n->key = std::move(key);
  n->entry = std::move(entry);
  const auto& roads = n->entry->net;
  n->planar = deform::make_planar(roads);
  n->rest_lonlat.reserve(roads.nodes.size());
  for (std::uint32_t i = 0; i < roads.nodes.size(); ++i) {
    n->node_by_id.emplace(roads.nodes[i].osm_id, i);
    n->rest_lonlat.push_back(roads.nodes[i].pos);
  }
  for (const auto& e : roads.edges) n->edge_keys.insert(edge_key(e.from, e.to));
  n->index = std::make_unique<deform::NodeIndex>(n->planar.nodes);
  const auto& lo = n->planar.min;
  const auto& hi = n->planar.max;
  double mx = 0.25 * (hi.x - lo.x) + 1, my = 0.25 * (hi.y - lo.y) + 1;
  n->unproject = deform::FastUnproject(n->planar.transform, {lo.x - mx, lo.y - my}, {hi.x + mx, hi.y + my});
  return n;
}

std::string weights_key(const deform::Weights& w) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "w=%.17g,%.17g,%.17g,%.17g", w.road, w.quad, w.smooth, w.guide);
  return buf;
}

}  // namespace

bool DeformNetwork::has_edge(std::uint32_t a, std::uint32_t b) const { return edge_keys.count(edge_key(a, b)) != 0; }

std::size_t DeformNetwork::memory_bytes() const {
  // Vectors by capacity; hash tables at ~48 bytes a node (key, value, next pointer, bucket);
  // the R-tree index at ~48 bytes a point.
  const std::size_t nodes = planar.nodes.size();
  return sizeof(DeformNetwork) + planar.nodes.capacity() * sizeof(geo::XY) +
         planar.edges.capacity() * sizeof(planar.edges[0]) + rest_lonlat.capacity() * sizeof(geo::LonLat) +
         node_by_id.size() * 48 + edge_keys.size() * 40 + nodes * 48;
}

DeformService::DeformService(Catalog& catalog, DeformLimits limits)
    : catalog_(catalog),
      limits_(limits),
      networks_(limits.network_cache_bytes),
      prepared_(limits.prepared_cache_bytes),
      results_(limits.result_cache_bytes) {}

DeformService::CacheStats DeformService::cache_stats() const {
  return {networks_.size(), prepared_.size(), results_.size(), results_.used(), networks_.used(), prepared_.used()};
}

std::shared_ptr<const DeformNetwork> DeformService::network_for(const DeformRequest& r) {
  if (r.roads_inline) {
    auto key = "inline:" + util::hex64(util::fnv1a64(r.roads_inline->dump()));
    if (auto hit = networks_.get(key)) return *hit;
    auto entry = std::make_shared<RoadNetworkEntry>();
    entry->net = parse_inline_roads(*r.roads_inline, "roads", limits_.max_inline_vertices);
    entry->info.id = "inline";
    entry->info.name = "inline";
    entry->info.node_count = entry->net.nodes.size();
    entry->info.edge_count = entry->net.edges.size();
    entry->info.way_count = entry->net.ways.size();
    auto net = make_network(key, entry);
    networks_.put(key, net, net->memory_bytes());
    return net;
  }
  require_slug(r.roads_id, "road network", "roads");
  auto entry = catalog_.road_network(r.roads_id);
  if (!entry) throw ApiError(404, "not_found", "roads: no road network '" + r.roads_id + "'", "roads");
  auto key = entry->info.id + "@" + std::to_string(entry->info.version);
  if (auto hit = networks_.get(key)) return *hit;
  auto net = make_network(key, entry);
  networks_.put(key, net, net->memory_bytes());
  return net;
}

std::shared_ptr<deform::Prepared> DeformService::prepared_for(const DeformRequest& r, const DeformNetwork& net,
                                                              const std::vector<std::uint32_t>& guide_nodes,
                                                              bool* cache_hit, std::string* key_out) {
  std::string key = net.key + "|" + r.grid.describe() + "|" + weights_key(r.weights) + "|" +
                    (r.boundary == deform::Boundary::fixed ? "fixed" : "sliding") + "|g=";
  for (auto g : guide_nodes) key += std::to_string(g) + ",";
  *key_out = key;
  *cache_hit = true;
  if (auto hit = prepared_.get(key)) return *hit;

  // One build per key at a time: concurrent identical requests wait for it.
  bool built = false;
  auto p = building_.run(key, [&] { return build_prepared(r, net, guide_nodes); }, &built);
  if (built) prepared_.put(key, p, p->memory_bytes());
  *cache_hit = !built;
  return p;
}

std::shared_ptr<deform::Prepared> DeformService::build_prepared(const DeformRequest& r, const DeformNetwork& net,
                                                                const std::vector<std::uint32_t>& guide_nodes) const {
  const auto& planar = net.planar;
  if (r.grid.kind == GridChoice::Kind::edges) {
    if (2 * planar.nodes.size() > limits_.max_unknowns)
      throw ApiError(413, "too_large", "grid: the edge-level method would need more than " +
                                           std::to_string(limits_.max_unknowns) + " unknowns", "grid");
    return std::make_shared<deform::Prepared>(deform::prepare_edges(planar, guide_nodes, r.weights));
  }
  grid::Grid g;
  if (r.grid.kind == GridChoice::Kind::uniform) {
    g = grid::build_uniform(grid::frame_around(planar.nodes, r.grid.n));
  } else {
    std::vector<geo::XY> special;
    for (auto n : guide_nodes) special.push_back(planar.nodes[n]);
    auto frame = grid::frame_around(planar.nodes, r.grid.base);
    if (grid::lattice_cells(frame, r.grid.depth) > limits_.max_lattice_cells)
      throw ApiError(413, "too_large",
                     "grid: base " + std::to_string(r.grid.base) + " at depth " + std::to_string(r.grid.depth) +
                         " is finer than " + std::to_string(limits_.max_lattice_cells) + " finest cells; lower base or depth",
                     "grid");
    g = grid::build_adaptive(frame, planar.nodes, special, {r.grid.base, r.grid.depth, r.grid.c});
  }
  // Limits are in unknowns (2 per grid vertex: x and y), as documented; the fixed boundary's
  // vertices count too, so this is an upper bound known before any assembly.
  std::size_t limit = r.solver == deform::SolverKind::cholesky ? limits_.max_direct_grid_unknowns : limits_.max_unknowns;
  if (2 * g.vertices.size() > limit)
    throw ApiError(413, "too_large",
                   "grid: " + std::to_string(g.vertices.size()) + " grid vertices (" +
                       std::to_string(2 * g.vertices.size()) + " unknowns) exceed the limit of " +
                       std::to_string(limit) + " unknowns for the " +
                       (r.solver == deform::SolverKind::cholesky ? "Cholesky solver; use \"solver\": \"cg\" or" : "solvers; use") +
                       " a coarser grid",
                   "grid");
  return std::make_shared<deform::Prepared>(deform::prepare_grid(planar, std::move(g), guide_nodes, r.weights, r.boundary));
}

namespace {

// The request's inputs as deformation targets in map units; validation errors name the field.
deform::Targets targets_for(const DeformRequest& r, const DeformNetwork& net, std::size_t* scaled_edges) {
  const auto& planar = net.planar;
  const auto& transform = planar.transform;
  deform::Targets targets;
  *scaled_edges = 0;
  if (r.app == DeformApp::focus) {
    std::vector<deform::FocusRegion> regions;
    for (const auto& in : r.regions) {
      deform::FocusRegion fr;
      fr.scale = in.scale;
      if (in.polygon.empty()) {
        fr.center = transform.to_map(*in.center);
        fr.radius = in.radius_m / transform.metres_per_unit;
      } else {
        for (const auto& p : in.polygon) fr.polygon.push_back(transform.to_map(p));
      }
      regions.push_back(std::move(fr));
    }
    targets.edge_scale = deform::focus_edge_scales(planar, regions);
    for (double s : targets.edge_scale) *scaled_edges += s != 1.0;
  }
  auto node_index = [&](std::int64_t id, const std::string& field) {
    auto it = net.node_by_id.find(id);
    if (it == net.node_by_id.end()) throw bad(field, "no road vertex " + std::to_string(id) + " in this network");
    return it->second;
  };
  std::vector<deform::Guide> guides;
  if (r.app == DeformApp::mental) {
    for (std::size_t i = 0; i < r.guides.size(); ++i) {
      const auto& g = r.guides[i];
      auto field = "guides[" + std::to_string(i) + "]";
      auto node = g.vertex ? node_index(*g.vertex, field + ".vertex") : net.index->nearest(transform.to_map(*g.point));
      guides.push_back({node, transform.to_map(g.target)});
    }
  }
  if (r.app == DeformApp::destination) {
    std::vector<std::uint32_t> route;
    std::unordered_set<std::uint32_t> seen;
    for (std::size_t i = 0; i < r.route.size(); ++i) {
      auto field = "route[" + std::to_string(i) + "]";
      auto node = node_index(r.route[i], field);
      if (!seen.insert(node).second) throw bad(field, "road vertex " + std::to_string(r.route[i]) + " repeats");
      if (!route.empty() && !net.has_edge(route.back(), node))
        throw bad(field, "road vertices " + std::to_string(r.route[i - 1]) + " and " + std::to_string(r.route[i]) +
                             " are not joined by a road edge");
      route.push_back(node);
    }
    std::vector<geo::XY> sketch;
    for (const auto& p : r.sketch) sketch.push_back(transform.to_map(p));
    sketch = deform::simplify_polyline(sketch, r.simplify_m / transform.metres_per_unit);
    guides = deform::route_to_sketch(planar, route, sketch);
  }
  targets.guides = deform::sorted_guides(guides);
  return targets;
}

nlohmann::json grid_json(const grid::Grid& g, const std::vector<geo::XY>& deformed, const DeformNetwork& net) {
  nlohmann::json quads = nlohmann::json::array(), before = nlohmann::json::array(), after = nlohmann::json::array(),
                 tj = nlohmann::json::array();
  for (const auto& q : g.quads) quads.push_back({q.corners[0], q.corners[1], q.corners[2], q.corners[3]});
  for (std::size_t i = 0; i < g.vertices.size(); ++i) {
    before.push_back(position(net.unproject(g.vertices[i])));
    after.push_back(position(net.unproject(deformed[i])));
  }
  for (const auto& t : g.tjunctions) tj.push_back({t.vertex, t.coarse_quad});
  return {{"quads", std::move(quads)}, {"before", std::move(before)}, {"after", std::move(after)}, {"tjunctions", std::move(tj)}};
}

nlohmann::json stats_json(const DeformRequest& r, const DeformNetwork& net, const deform::Prepared& p,
                          const deform::Targets& targets, const deform::RunResult& result, bool prepared_hit,
                          std::size_t scaled_edges) {
  const auto& s = result.solve;
  return {{"method", r.grid.describe()},
          {"solver", s.kind == deform::SolverKind::cg ? "cg" : "cholesky"},
          {"residue", result.residue},
          {"residue_rest", deform::residue(net.planar, targets, net.planar.nodes)},
          {"road_edges", net.planar.edges.size()},
          {"scaled_edges", scaled_edges},
          {"guides", targets.guides.size()},
          {"unknowns", p.rest_unknowns.size()},
          {"quads", p.grid ? p.grid->quads.size() : 0},
          {"grid_edges", p.grid ? grid::count_grid_edges(*p.grid) : 0},
          {"support_edges", p.support_edges},
          {"iterations", s.iterations},
          {"converged", s.converged},
          {"relative_residual", s.relative_residual},
          {"foldovers", result.inverted_quads},
          {"crossings_added", result.crossings_added ? nlohmann::json(*result.crossings_added) : nlohmann::json(nullptr)},
          {"relax_iterations", result.relax_iterations},
          {"untangle_steps", result.untangle_steps},
          {"untangle_left", result.untangle_left},
          {"cache", prepared_hit ? "hit" : "miss"},
          {"assembly_ms", prepared_hit ? 0.0 : p.assembly_ms},
          {"factor_ms", s.factor_ms},
          {"solve_ms", s.solve_ms},
          {"rhs_ms", result.rhs_ms},
          {"place_ms", result.place_ms}};
}

}  // namespace

Response DeformService::handle(DeformApp app, const Request& req) {
  auto started = Clock::now();
  auto r = parse_deform_request(app, parse_json_body(req), limits_);
  auto net = network_for(r);
  std::size_t scaled_edges = 0;
  auto targets = targets_for(r, *net, &scaled_edges);

  // Positions as binary (api/positions_binary.hpp) for a client that asks for them.
  const bool binary = accepts_octet_stream(req.accept);
  if (binary && r.roads_output != DeformRequest::RoadsOutput::positions)
    throw ApiError(406, "not_acceptable",
                   "output.roads: Accept: application/octet-stream answers only \"output\": {\"roads\": \"positions\"}",
                   "output.roads");
  const char* content_type = binary ? "application/octet-stream" : "application/json";
  std::string result_key = net->key + "|" + app_name(app) + "|" + r.canonical + (binary ? "|binary" : "");
  if (auto hit = results_.get(result_key)) {
    Response cached;
    cached.body = **hit;
    cached.content_type = content_type;
    cached.headers.emplace_back("X-Result-Cache", "hit");
    return cached;
  }

  bool prepared_hit = false;
  std::string prepared_key;
  auto prepared = prepared_for(r, *net, deform::guide_nodes(targets.guides), &prepared_hit, &prepared_key);
  if (r.solver == deform::SolverKind::cholesky && prepared->grid &&
      static_cast<std::size_t>(prepared->rest_unknowns.size()) > limits_.max_direct_grid_unknowns)
    throw ApiError(413, "too_large",
                   "grid: " + std::to_string(prepared->rest_unknowns.size()) +
                       " unknowns are too many for the Cholesky solver (at most " +
                       std::to_string(limits_.max_direct_grid_unknowns) + "); use \"solver\": \"cg\" or a coarser grid",
                   "grid");
  deform::RunOptions options;
  options.solve.kind = r.solver;
  options.solve.max_iterations = r.max_iterations;
  options.solve.tolerance = r.tolerance;
  options.solve.time_limit_ms = r.time_limit_ms;
  options.relax = r.relax;
  options.count_crossings = r.check_crossings;
  auto result = deform::run(*prepared, net->planar, targets, options);
  // The first Cholesky solve factorized: the cache charges the factor's bytes from now on.
  if (result.solve.kind == deform::SolverKind::cholesky && !result.solve.factor_cached)
    prepared_.put(prepared_key, prepared, prepared->memory_bytes());

  auto out_start = Clock::now();
  std::vector<geo::LonLat> deformed;
  deformed.reserve(result.nodes.size());
  for (const auto& p : result.nodes) deformed.push_back(net->unproject(p));

  nlohmann::json out = {{"app", app_name(app)}, {"roads_id", net->entry->info.id}, {"version", net->entry->info.version}};
  if (!r.map_points.empty()) {
    std::vector<geo::XY> queries;
    for (const auto& p : r.map_points) queries.push_back(net->planar.transform.to_map(p));
    nlohmann::json mapped = nlohmann::json::array();
    for (const auto& p : deform::map_points(*prepared, result.points, result.nodes, net->planar.nodes, *net->index, queries))
      mapped.push_back(position(net->unproject(p)));
    out["mapped_points"] = std::move(mapped);
  }
  out["grid"] = r.grid_output && prepared->grid ? grid_json(*prepared->grid, result.points, *net) : nlohmann::json(nullptr);
  if (!targets.guides.empty()) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& g : targets.guides)
      list.push_back({{"vertex", net->entry->net.nodes[g.node].osm_id},
                      {"from", position(net->rest_lonlat[g.node])},
                      {"target", position(net->unproject(g.target))},
                      {"to", position(deformed[g.node])}});
    out["guides"] = std::move(list);
  }
  out["attribution"] = nlohmann::json::array();
  if (!net->entry->info.attribution.empty()) out["attribution"].push_back(net->entry->info.attribution);
  // The big part (roads or positions) is written as text and spliced in front of the rest.
  std::string roads_text;
  if (binary) {
    // No positions in the text: they follow it as float32 pairs.
  } else if (r.roads_output == DeformRequest::RoadsOutput::geojson) {
    roads_text = R"({"roads":)" + roads_geojson(*net->entry, std::nullopt, false, &deformed) + ",";
  } else if (r.roads_output == DeformRequest::RoadsOutput::positions) {
    roads_text = R"({"positions":)";
    append_flat_positions(roads_text, deformed);
    roads_text += ',';
  }
  auto stats = stats_json(r, *net, *prepared, targets, result, prepared_hit, scaled_edges);
  stats["output_ms"] = ms_since(out_start);
  stats["total_ms"] = ms_since(started);
  out["stats"] = std::move(stats);

  Response resp = json_response(out);
  if (!roads_text.empty()) resp.body = roads_text + resp.body.substr(1);
  if (binary) {
    resp.body = encode_positions_binary(resp.body, deformed);
    resp.content_type = content_type;
  }
  results_.put(result_key, std::make_shared<const std::string>(resp.body), resp.body.size());
  return resp;
}

}  // namespace tourmap::api
