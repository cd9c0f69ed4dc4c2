// Deformation benchmark (paper 4.5, Fig. 4.4f / 4.7e) on the shared road networks, with
// tables for:
//   1. methods: edge-level baseline, uniform 20/40/80, adaptive depth 1-4 on a 10x10 base,
//      for a focus map (three regions, Z = 3) and a mental map (vertices pulled onto a circle):
//      unknowns, grid edges, time (assembly, Cholesky first solve and re-solve, CG), residue,
//      foldovers, crossings added; the ratio columns compare with uniform 80x80 in the same run;
//   2. scaling: time vs road edges over every network;
//   3. interactive: the largest network through the API's deformation service (request JSON in,
//      response JSON out): first request, then re-solves for a focus region dragged in 40 steps.
// Times are medians over repeated runs.
//
//   build/bench/deform_bench [--data-dir DIR] [--quick]

#include "api/catalog.hpp"
#include "api/deform_service.hpp"
#include "deform/applications.hpp"
#include "deform/deformer.hpp"
#include "load/osm_roads.hpp"
#include "store/importer.hpp"
#include "store/migrate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <queue>
#include <tuple>
#include <string>
#include <vector>

namespace {

using namespace tourmap;
using namespace tourmap::deform;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}
double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[std::min(v.size() - 1, static_cast<std::size_t>(q * v.size()))];
}

struct Method {
  std::string name;
  enum Kind { edges, uniform, adaptive } kind;
  int n_or_depth = 0;
};

const std::vector<Method> kMethods = {{"edge-level", Method::edges, 0},     {"uniform 20", Method::uniform, 20},
                                      {"uniform 40", Method::uniform, 40},  {"uniform 80", Method::uniform, 80},
                                      {"adaptive d1", Method::adaptive, 1}, {"adaptive d2", Method::adaptive, 2},
                                      {"adaptive d3", Method::adaptive, 3}, {"adaptive d4", Method::adaptive, 4}};

Prepared prepare(const Method& m, const PlanarNetwork& net, const std::vector<std::uint32_t>& guides) {
  Weights w;
  if (m.kind == Method::edges) return prepare_edges(net, guides, w);
  if (m.kind == Method::uniform)
    return prepare_grid(net, grid::build_uniform(grid::frame_around(net.nodes, m.n_or_depth)), guides, w, Boundary::fixed);
  std::vector<XY> special;
  for (auto g : guides) special.push_back(net.nodes[g]);
  return prepare_grid(net,
                      grid::build_adaptive(grid::frame_around(net.nodes, 10), net.nodes, special, {10, m.n_or_depth, 4}),
                      guides, w, Boundary::fixed);
}

// Three focus regions (Z = 3) around the densest part: the road nodes nearest to the centre
// and two points 15% of the map away, each 6% of the map in radius.
Targets focus_workload(const PlanarNetwork& net, double shift = 0.0) {
  NodeIndex index(net.nodes);
  std::vector<FocusRegion> regions;
  XY mid{(net.min.x + net.max.x) / 2, (net.min.y + net.max.y) / 2};
  for (XY offset : {XY{0, 0}, XY{150, 100}, XY{-150, -100}}) {
    auto c = net.nodes[index.nearest({mid.x + offset.x, mid.y + offset.y})];
    regions.push_back({{}, {c.x + shift, c.y}, 60.0, 3.0});
  }
  Targets t;
  t.edge_scale = focus_edge_scales(net, regions);
  return t;
}

// A mental map: 24 road vertices nearest to a circle (radius 15% of the map) are pulled onto it.
Targets mental_workload(const PlanarNetwork& net) {
  NodeIndex index(net.nodes);
  XY mid{(net.min.x + net.max.x) / 2, (net.min.y + net.max.y) / 2};
  std::vector<Guide> guides;
  for (int i = 0; i < 24; ++i) {
    double a = 2 * M_PI * i / 24;
    XY target{mid.x + 150 * std::cos(a), mid.y + 150 * std::sin(a)};
    guides.push_back({index.nearest(target), target});
  }
  Targets t;
  t.guides = sorted_guides(guides);  // two circle points may snap to one vertex: the later wins
  return t;
}

// A destination map: the shortest route between the road nodes nearest to points 30 % of the map
// left and right of the centre, pulled onto the straight line between its ends.
Targets destination_workload(const PlanarNetwork& net) {
  const std::size_t n = net.nodes.size();
  std::vector<std::vector<std::pair<std::uint32_t, double>>> adj(n);
  for (auto [a, b] : net.edges) {
    const double d = std::hypot(net.nodes[a].x - net.nodes[b].x, net.nodes[a].y - net.nodes[b].y);
    adj[a].push_back({b, d});
    adj[b].push_back({a, d});
  }
  NodeIndex index(net.nodes);
  XY mid{(net.min.x + net.max.x) / 2, (net.min.y + net.max.y) / 2};
  const double w = net.max.x - net.min.x, h = net.max.y - net.min.y;
  const auto s = index.nearest({mid.x - 0.3 * w, mid.y - 0.1 * h});
  std::vector<double> dist(n, 1e300);
  std::vector<std::uint32_t> prev(n, static_cast<std::uint32_t>(n));
  std::priority_queue<std::pair<double, std::uint32_t>, std::vector<std::pair<double, std::uint32_t>>, std::greater<>> q;
  dist[s] = 0;
  q.push({0, s});
  while (!q.empty()) {
    auto [d, u] = q.top();
    q.pop();
    if (d > dist[u]) continue;
    for (auto [v, len] : adj[u])
      if (d + len < dist[v]) dist[v] = d + len, prev[v] = u, q.push({dist[v], v});
  }
  const XY end_point{mid.x + 0.3 * w, mid.y + 0.1 * h};
  std::uint32_t e = s;
  double best = 1e300;
  for (std::uint32_t v = 0; v < n; ++v) {
    const double d = std::hypot(net.nodes[v].x - end_point.x, net.nodes[v].y - end_point.y);
    if (dist[v] < 1e300 && d < best) best = d, e = v;
  }
  std::vector<std::uint32_t> route;
  for (auto v = e; v != n; v = prev[v]) route.insert(route.begin(), v);
  Targets t;
  t.guides = sorted_guides(route_to_sketch(net, route, {net.nodes[s], net.nodes[e]}));
  return t;
}

struct Row {
  std::string method;
  std::size_t unknowns = 0, grid_edges = 0, quads = 0;
  double assembly = 0, first = 0, resolve = 0, cg = 0;
  int cg_iterations = 0;
  bool cg_converged = false;
  double residue = 0;
  std::size_t foldovers = 0, crossings = 0;
};

Row measure(const Method& m, const PlanarNetwork& net, const Targets& t, int repeats) {
  Row row;
  row.method = m.name;
  std::vector<double> assembly, first, resolve, cg;
  RunResult last;
  for (int rep = 0; rep < repeats; ++rep) {
    auto start = Clock::now();
    auto p = prepare(m, net, guide_nodes(t.guides));
    assembly.push_back(ms_since(start));
    RunOptions o;
    last = run(p, net, t, o);
    first.push_back(ms_since(start));
    auto again = Clock::now();
    run(p, net, t, o);
    resolve.push_back(ms_since(again));
    RunOptions c;
    c.solve.kind = SolverKind::cg;
    c.solve.tolerance = 1e-8;
    c.solve.time_limit_ms = 20000;
    auto cg_start = Clock::now();
    auto it = run(p, net, t, c);
    cg.push_back(ms_since(cg_start) + assembly.back());
    row.cg_iterations = it.solve.iterations;
    row.cg_converged = it.solve.converged;
    row.unknowns = static_cast<std::size_t>(p.rest_unknowns.size());
    row.grid_edges = p.grid ? grid::count_grid_edges(*p.grid) + p.support_edges : 0;
    row.quads = p.grid ? p.grid->quads.size() : 0;
  }
  row.assembly = median(assembly);
  row.first = median(first);
  row.resolve = median(resolve);
  row.cg = median(cg);
  row.residue = last.residue;
  row.foldovers = last.inverted_quads;
  row.crossings = count_added_crossings(net, last.nodes);
  return row;
}

void print_methods(const std::string& title, const std::string& network, const PlanarNetwork& net, const Targets& t,
                   int repeats) {
  std::printf("\n### %s: %s (%zu road edges, %zu nodes; residue at rest %.1f)\n\n", title.c_str(), network.c_str(),
              net.edges.size(), net.nodes.size(), residue(net, t, net.nodes));
  std::printf("| method | unknowns | quads | grid edges | assembly ms | Cholesky first ms | re-solve ms | CG ms (iters) | residue | first vs u80 | residue vs u80 | foldovers | crossings added |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::vector<Row> rows;
  for (const auto& m : kMethods) rows.push_back(measure(m, net, t, repeats));
  const Row& u80 = rows[3];
  for (const auto& r : rows)
    std::printf("| %s | %zu | %zu | %zu | %.1f | %.1f | %.2f | %.1f (%d%s) | %.1f | %.2fx | %.3f | %zu | %zu |\n",
                r.method.c_str(), r.unknowns, r.quads, r.grid_edges, r.assembly, r.first, r.resolve, r.cg,
                r.cg_iterations, r.cg_converged ? "" : ", not converged", r.residue, r.first / u80.first,
                r.residue / u80.residue, r.foldovers, r.crossings);
  for (const auto& r : rows)
    if (r.method.rfind("adaptive", 0) == 0 && r.residue <= u80.residue) {
      std::printf("\n%s reaches uniform 80x80's residue (%.1f <= %.1f) in %.1f ms vs %.1f ms (%.2fx; CG %.1f vs %.1f ms).\n",
                  r.method.c_str(), r.residue, u80.residue, r.first, u80.first, r.first / u80.first, r.cg, u80.cg);
      return;
    }
  std::printf("\nNo adaptive depth up to 4 reaches uniform 80x80's residue on this network.\n");
}

void print_scaling(const std::vector<std::pair<std::string, PlanarNetwork>>& nets, int repeats) {
  std::printf("\n### Scaling: focus map (three regions, Z = 3), time vs road edges\n\n");
  std::printf("| network | road edges | adaptive d3 unknowns | adaptive d3 first ms | re-solve ms | CG ms | uniform 80 first ms | edge-level first ms | edge-level CG ms |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& [name, net] : nets) {
    auto t = focus_workload(net);
    auto a = measure(kMethods[6], net, t, repeats);
    auto u = measure(kMethods[3], net, t, repeats);
    auto e = measure(kMethods[0], net, t, repeats);
    std::printf("| %s | %zu | %zu | %.1f | %.2f | %.1f | %.1f | %.1f | %.1f |\n", name.c_str(), net.edges.size(),
                a.unknowns, a.first, a.resolve, a.cg, u.first, e.first, e.cg);
  }
}

void print_interactive(const std::string& data_dir, const std::string& name, const std::string& file, int steps) {
  auto dir = std::filesystem::temp_directory_path() / ("tourmap-deform-bench-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  auto db_path = (dir / "bench.db").string();
  {
    store::Db db(db_path);
    store::migrate(db);
    store::import_roads(db, {{name, name, "OSM"}, data_dir + "/" + file, false});
  }
  store::DbPool pool(db_path);
  api::Catalog catalog(pool);
  api::DeformService service(catalog);
  auto info = catalog.road_network(name);
  auto c = info->info.bbox.center();

  std::printf("\n### Interactive: dragging a focus region on %s (%zu road edges) through the API service\n\n",
              name.c_str(), info->net.edges.size());
  std::printf("| output | first request ms | re-solve p50 ms | re-solve p95 ms | max ms | server solve p50 ms | response KiB | cache hits |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (std::string output : {"positions", "geojson", "none"}) {
    std::vector<double> times, solves;
    double first = 0;
    std::size_t bytes = 0;
    int hits = 0;
    for (int i = 0; i <= steps; ++i) {
      nlohmann::json body = {{"roads", name},
                             {"regions", {{{"center", {c.lon + 0.0004 * i, c.lat + 0.0002 * i}}, {"radius_m", 800}, {"scale", 3}}}},
                             {"output", {{"roads", output}, {"grid", false}}}};
      api::Request req;
      req.method = "POST";
      req.content_type = "application/json";
      req.body = body.dump();
      auto start = Clock::now();
      auto resp = service.handle(api::DeformApp::focus, req);
      double ms = ms_since(start);  // includes parsing the request and serialising the response
      auto stats = nlohmann::json::parse(resp.body)["stats"];
      if (i == 0) {
        first = ms;
        continue;
      }
      times.push_back(ms);
      solves.push_back(stats["solve_ms"].get<double>() + stats["rhs_ms"].get<double>());
      hits += stats["cache"] == "hit";
      bytes = resp.body.size();
    }
    std::printf("| %s | %.1f | %.2f | %.2f | %.2f | %.2f | %.0f | %d/%d |\n", output.c_str(), first,
                percentile(times, 0.5), percentile(times, 0.95), *std::max_element(times.begin(), times.end()),
                percentile(solves, 0.5), bytes / 1024.0, hits, steps);
  }
  std::filesystem::remove_all(dir);
}

// Fold-overs (4.4.2) of the three applications on every network, adaptive depth 3 (the API's
// default grid): the raw solve as it was (no T-junction snapping, no relaxation), with the
// T-junctions snapped, and the default (snapped and relaxed). Time: a re-solve on the prepared
// system plus placing and relaxing (what a drag step pays).
void print_foldovers(const std::vector<std::pair<std::string, PlanarNetwork>>& nets) {
  std::printf("\n### Fold-overs by default: raw solve vs T-junctions snapped vs default (snapped, relaxed, untangled; adaptive d3)\n\n");
  std::printf("| network | application | raw folds | raw crossings | snapped folds | snapped crossings | default folds | default crossings | relax steps | untangle steps (left) | residue raw | residue default | default vs raw | re-solve ms raw | re-solve ms default |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& [name, net] : nets) {
    const std::pair<const char*, Targets> apps[] = {
        {"focus", focus_workload(net)}, {"mental", mental_workload(net)}, {"destination", destination_workload(net)}};
    for (const auto& [app, t] : apps) {
      auto p = prepare(Method{"adaptive d3", Method::adaptive, 3}, net, guide_nodes(t.guides));
      RunOptions raw, snapped, relaxed;
      raw.relax = snapped.relax = false;
      raw.snap_tjunctions = false;
      run(p, net, t, relaxed);  // factor once
      auto timed = [&](const RunOptions& o) {
        auto start = Clock::now();
        auto r = run(p, net, t, o);
        const double ms = ms_since(start);
        return std::tuple{r, ms, count_added_crossings(net, r.nodes)};
      };
      auto [r0, ms0, c0] = timed(raw);
      auto [r1, ms1, c1] = timed(snapped);
      auto [r2, ms2, c2] = timed(relaxed);
      std::printf("| %s | %s | %zu | %zu | %zu | %zu | %zu | %zu | %d | %d (%zu) | %.1f | %.1f | %.2fx | %.2f | %.2f |\n",
                  name.c_str(), app, r0.inverted_quads, c0, r1.inverted_quads, c1, r2.inverted_quads, c2, r2.relax_iterations,
                  r2.untangle_steps, r2.untangle_left,
                  r0.residue, r2.residue, r2.residue / std::max(r0.residue, 1e-12), ms0, ms2);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string data_dir = TOURMAP_DEFAULT_DATA_DIR;
  if (const char* env = std::getenv("TOURMAP_DATA_DIR")) data_dir = env;
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--data-dir" && i + 1 < argc) data_dir = argv[++i];
    if (a == "--quick") quick = true;
  }
  int repeats = quick ? 1 : 3;
  struct Source {
    const char* name;
    const char* file;
  };
  const std::vector<Source> sources = {{"west-oakland", "roads/West-Oakland.osm.bz2"},
                                       {"berlin-siegessaeule", "roads/berlin-siegessaeule.osm.gz"},
                                       {"krems", "roads/krems.osm.gz"},
                                       {"monaco", "roads/monaco.osm.gz"},
                                       {"north-bayreuth", "roads/north-bayreuth.osm.gz"},
                                       {"andorra", "roads/andorra.osm.gz"},
                                       {"liechtenstein", "roads/liechtenstein-latest.osm.pbf"}};
  std::vector<std::pair<std::string, PlanarNetwork>> nets;
  for (const auto& s : sources) nets.emplace_back(s.name, make_planar(load::load_osm_roads(data_dir + "/" + s.file)));
  auto find = [&](const std::string& n) -> const PlanarNetwork& {
    for (const auto& [name, net] : nets)
      if (name == n) return net;
    std::abort();
  };

  std::printf("# tourmap deformation benchmark\n\nMap units: longer bbox side = 1000. Weights: defaults "
              "(road 1, quad 0.3, smooth 0.5, guide 100). Adaptive: base 10, c = 4. Times are medians of %d run(s) on "
              "this machine; \"first\" = build grid + assemble + factor + solve + place roads.\n",
              repeats);
  for (const char* n : {"monaco", "north-bayreuth", "liechtenstein"})
    print_methods("Focus map", n, find(n), focus_workload(find(n)), repeats);
  for (const char* n : {"berlin-siegessaeule", "monaco"})
    print_methods("Mental map", n, find(n), mental_workload(find(n)), repeats);
  print_foldovers(nets);
  print_scaling(nets, repeats);
  print_interactive(data_dir, "liechtenstein", "roads/liechtenstein-latest.osm.pbf", quick ? 10 : 40);
  return 0;
}
