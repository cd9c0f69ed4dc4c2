// Metro map benchmark (paper 5.5): the chapter-5 pipeline (core/metro/city_layout.hpp: visual
// worth -> edge lengths -> pre-layout -> octilinear grid routing -> [MIP] -> warping) on every
// shared network, beside loom/octi. Links tourmap_core only: the networks and POIs come from
// the core loaders, as scripts/sample-data.json has the sample import read them.
//
// One table: per network, the default request (lengths=visual-worth) and lengths=uniform, both
// with solver=fast (the default request's path once the MIP runs in the background); --mip
// adds both with solver=mip (CBC in this process, for the rest of the time limit). Bends,
// displacement, min/mean edge, octilinear share and edges kept are metro_compare.py's
// definitions (core/metro/layout_metrics.hpp), so they stand beside octi's figures from
// ../shared/tools/README.md; min gap, added crossings and order violations are tourmap's
// quality report (core/metro/layout_quality.hpp). Times: the layout computation in this
// process (one run, first computation); octi's: its whole process (median of 3).
//
//   build/bench/metro_bench [--data-dir DIR] [--city ID] [--mip] [--time-limit S]
//                           [--write-layouts DIR]   (or TOURMAP_BENCH_LAYOUTS=DIR) [--variants]
//                           [--unlabelled PX]  (also list the stations without a name at that zoom)
// --variants: instead, networks the layout has not seen (bench/metro_variants.hpp: every
// manifest network jittered, without its longest line, and with flaws), default request: do
// the invariants hold (0 added crossings and order violations, octilinear, every edge kept,
// min gap >= 0.5 mean edge, within the time budget)?
// --write-layouts writes each layout as DIR/<network>-<request>.json (stations and edges in the
// API's frame, the fields metro_compare.py reads), to check the figures:
//   python3 ../shared/tools/metro_compare.py measure ../shared/data/metro/loom_wien.json DIR/vienna-default.json

#include "load/file.hpp"
#include "load/metro_load.hpp"
#include "load/metro_rules_json.hpp"
#include "load/name_rules.hpp"
#include "load/poi_load.hpp"
#include "metro/city_layout.hpp"
#include "metro/layout_metrics.hpp"
#include "metro_variants.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace tourmap;

// loom/octi (default heuristic) measured with metro_compare.py: ../shared/tools/README.md,
// "Reference: loom/octi", loom commit 1e47578, same 2-core machine, whole process, median of 3.
struct Reference {
  const char* network;   // the sample import's city id
  const char* tool_input;  // metro_compare.py's INPUT for this network (under the data dir)
  double octi_s;
  int octi_bends;
  double octi_min_mean_edge;
  double octi_displacement_pct;
};
constexpr Reference kNetworks[] = {
    {"freiburg", "metro/loom_freiburg.json", 0.07, 10, 0.718, 2.84},
    {"vienna", "metro/loom_wien.json", 0.11, 16, 0.491, 3.22},
    {"chicago", "metro/loom_chicago.json", 0.31, 14, 0.230, 3.10},
    {"berlin", "metro/loom_berlin.json", 0.20, 20, 0.595, 2.30},
    {"sydney", "metro/loom_sydney.json", 0.16, 23, 0.458, 2.23},
    {"stuttgart", "metro/loom_stuttgart.json", 0.24, 23, 0.475, 2.58},
    {"london", "metro/london.loom.json", 12.31, 62, 0.183, 2.29},
};

struct City {
  model::MetroNetwork net;
  std::vector<model::Poi> pois;
};

// The city as the sample import has it: its manifest entry's metro files and POIs.
City load_city(const nlohmann::json& entry, const std::string& data_dir) {
  City c;
  const auto& metro = entry.at("metro");
  std::vector<std::string> files;
  for (const auto& f : metro.at("files")) files.push_back(data_dir + "/" + f.get<std::string>());
  const auto format = metro.at("format").get<std::string>();
  if (format == "loom") c.net = load::load_metro_loom(files.at(0));
  else if (format == "station-csvs") c.net = load::load_metro_station_csvs(files.at(0), files.at(1), files.at(2));
  else c.net = load::load_metro_line_csv(files.at(0));
  // The names as users see them (the manifest's name rules); every line kept, so that the
  // written layouts match metro_compare.py's input (the import hides construction lines).
  if (metro.contains("rules")) {
    auto rules = load::parse_metro_rules(metro["rules"], "metro.rules");
    rules.hide_lines.clear();
    rules.lines.clear();
    load::apply_metro_rules(c.net, rules);
  }
  if (entry.contains("pois"))
    c.pois = load::load_pois(data_dir + "/" + entry["pois"].at("file").get<std::string>(),
                             {entry["pois"].value("category", "")});
  return c;
}

// The layout in the API's frame (metres): what the API's answer draws.
metro::Layout in_frame(const metro::CityLayoutResult& r) {
  metro::Layout out;
  out.pos = r.frame.nodes;
  for (const auto& path : r.layout.paths) {
    out.paths.emplace_back();
    for (const auto& p : path) out.paths.back().push_back(r.frame.frame.apply(p));
  }
  return out;
}

// The fields of the API's answer that metro_compare.py reads (read_tourmap).
void write_layout(const std::string& path, const model::MetroNetwork& net, const metro::Layout& L) {
  auto xy = [](metro::XY p) { return nlohmann::json::array({p.x, p.y}); };
  auto lines = [&](const std::vector<std::uint32_t>& idx) {
    nlohmann::json ids = nlohmann::json::array();
    for (auto l : idx) ids.push_back(net.lines[l].id);
    return ids;
  };
  nlohmann::json stations = nlohmann::json::array(), edges = nlohmann::json::array();
  for (std::size_t v = 0; v < net.nodes.size(); ++v) {
    const auto& n = net.nodes[v];
    if (!n.is_station()) continue;
    stations.push_back({{"type", "Feature"},
                        {"id", n.id},
                        {"geometry", {{"type", "Point"}, {"coordinates", xy(L.pos[v])}}},
                        {"properties", {{"id", n.id}, {"station_id", n.station_id}, {"name", n.name}}}});
  }
  for (std::size_t e = 0; e < net.edges.size(); ++e) {
    nlohmann::json coords = nlohmann::json::array();
    for (const auto& p : L.paths[e]) coords.push_back(xy(p));
    edges.push_back({{"type", "Feature"},
                     {"geometry", {{"type", "LineString"}, {"coordinates", std::move(coords)}}},
                     {"properties", {{"from", net.nodes[net.edges[e].from].id},
                                     {"to", net.nodes[net.edges[e].to].id},
                                     {"lines", lines(net.edges[e].lines)}}}});
  }
  nlohmann::json doc = {{"stations", {{"type", "FeatureCollection"}, {"features", std::move(stations)}}},
                        {"edges", {{"type", "FeatureCollection"}, {"features", std::move(edges)}}}};
  std::ofstream(path) << doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
}

// "fast ok", or the MIP's status and whether its layout was kept (else why not).
std::string solver_text(const metro::SolverReport& s) {
  std::string out;
  if (!s.mip) return out.append(s.kind).append(" ").append(s.status);
  out.append("MIP ").append(s.mip->status);
  if (s.mip->accepted) out.append(", kept");
  else if (!s.mip->reason.empty()) out.append(", not kept: ").append(s.mip->reason);
  return out;
}

// A row of the "where the time goes" table.
std::string stage_row(const std::string& network, const std::string& request, const metro::CityLayoutResult& r) {
  const auto& t = r.timing;
  std::string attempts;
  for (const auto& a : r.route.attempts) {
    char one[96];
    std::snprintf(one, sizeof one, "%s%.0f ms%s", attempts.empty() ? "" : ", ", a.ms,
                  a.unrouted ? " (unrouted)" : a.added ? " (added)" : "");
    attempts += one;
  }
  char row[768];
  std::snprintf(row, sizeof row, "| %s | %s | %.0f | %.1f | %.1f | %.1f (%d, %zu) | %s | %.1f (%d) | %.1f (%d, %s) | %.1f | %.1f | %.1f |\n",
                network.c_str(), request.c_str(), t.total, t.visual_worth, t.prelayout, t.route, r.route.attempt,
                r.route.ripups, attempts.c_str(), t.bends, r.bends.rounds, t.spacing, r.spacing.rounds,
                r.spacing.status.c_str(), t.measure, t.layout - t.fast, t.warp);
  return row;
}

// A row of the line order table.
std::string order_row(const std::string& network, const std::string& request, const metro::CityLayoutResult& r) {
  const auto& o = r.line_order.report;
  char row[256];
  std::snprintf(row, sizeof row, "| %s | %s | %zu | %.1f | %zu | %zu | %.0f | %zu | %s |\n", network.c_str(), request.c_str(),
                o.pairs, r.timing.line_order, o.heuristic_crossings, o.crossings, o.lower_bound, o.separations,
                o.method.c_str());
  return row;
}

// A row of the labels table: time, and labelled / all at each scale.
// Overlaps among a scale's names (at its zoom and at 8 zooms up to `next_px_per_unit`, where a
// client still shows it), and names crossed by a line's centre (both must be 0), in layout
// units.
std::size_t label_overlaps(const metro::Layout& L, const metro::LabelScale& scale, double next_px_per_unit) {
  struct Box {
    double x0, y0, x1, y1;
  };
  const auto boxes_at = [&](double k) {
    std::vector<Box> boxes;
    for (const auto& l : scale.labels) {
      const auto p = L.pos[l.node];
      boxes.push_back({p.x + l.x0 / k, p.y - l.y1 / k, p.x + l.x1 / k, p.y - l.y0 / k});
    }
    return boxes;
  };
  std::size_t n = 0;
  for (int step = 0; step <= 8; ++step) {
    const double k = scale.px_per_unit + (next_px_per_unit - scale.px_per_unit) * step / 8 * (1 - 1e-6);
    const auto at = boxes_at(k);
    for (std::size_t i = 0; i < at.size(); ++i)
      for (std::size_t j = i + 1; j < at.size(); ++j) {
        const auto &a = at[i], &b = at[j];
        n += a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
      }
  }
  const auto boxes = boxes_at(scale.px_per_unit);
  // A line's centre through a name: clip each segment to each box (Liang-Barsky).
  for (const auto& b : boxes)
    for (const auto& path : L.paths)
      for (std::size_t i = 1; i < path.size(); ++i) {
        const auto a0 = path[i - 1], a1 = path[i];
        double t0 = 0, t1 = 1;
        const double dx = a1.x - a0.x, dy = a1.y - a0.y;
        const double pp[4] = {-dx, dx, -dy, dy}, q[4] = {a0.x - b.x0, b.x1 - a0.x, a0.y - b.y0, b.y1 - a0.y};
        bool in = true;
        for (int e = 0; e < 4 && in; ++e) {
          if (pp[e] == 0) {
            in = q[e] >= 0;
            continue;
          }
          const double t = q[e] / pp[e];
          if (pp[e] < 0) t0 = std::max(t0, t);
          else t1 = std::min(t1, t);
          in = t0 <= t1;
        }
        n += in;
      }
  return n;
}

// The names a client of `width` x `height` px shows with the whole network in view (and at
// twice that zoom): the largest served zoom at or below its own.
std::pair<std::size_t, std::size_t> named_in_view(const metro::CityLayoutResult& r, double width, double height) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300, mean = 0;
  for (const auto& p : r.layout.pos) x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  for (const auto& path : r.layout.paths)
    for (std::size_t i = 1; i < path.size(); ++i) mean += std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
  mean /= static_cast<double>(std::max<std::size_t>(1, r.layout.paths.size()));
  const double fit = std::min(width / std::max(x1 - x0, 1e-9), height / std::max(y1 - y0, 1e-9));
  const auto named = [&](double px_per_unit) {
    std::size_t n = 0;
    for (const auto& scale : r.labels)
      if (scale.mean_edge_px <= mean * px_per_unit * (1 + 1e-9)) n = scale.labels.size();
    return n;
  };
  return {named(fit), named(2 * fit)};
}

std::string labels_row(const std::string& network, const std::string& request, const metro::CityLayoutResult& r,
                       std::size_t stations) {
  std::size_t overlaps = 0;
  for (std::size_t k = 0; k < r.labels.size(); ++k)
    overlaps += label_overlaps(r.layout, r.labels[k],
                               k + 1 < r.labels.size() ? r.labels[k + 1].px_per_unit : 4 * r.labels[k].px_per_unit);
  const auto [fit, twice] = named_in_view(r, 1200, 720);
  char cell[160];
  std::snprintf(cell, sizeof cell, "| %s | %s | %.0f | %zu/%zu | %zu/%zu | %zu |", network.c_str(), request.c_str(), r.timing.labels,
                fit, stations, twice, stations, overlaps);
  std::string row = cell;
  for (const auto& scale : r.labels) {
    std::snprintf(cell, sizeof cell, " %zu/%zu |", scale.labels.size(), stations);
    row.append(cell);
  }
  const auto& room = r.solver.label_room;
  std::snprintf(cell, sizeof cell, " %s: %d/%d+%d, %zu -> %zu, %.0f ms |", room.status.c_str(), room.kept, room.rounds,
                room.single_tries, room.unnamed_before, room.unnamed_after, r.timing.label_room);
  row.append(cell);
  return row.append("\n");
}

void print_labels(const std::vector<std::string>& rows) {
  std::printf("\n## Station names\n\nThe placement's time for all zooms; stations named in a 1200 x 720 px view of the "
              "whole network and at twice that zoom; overlaps of names with names (at every zoom a placement is "
              "shown at, up to the next one's) or with a line's centre, over all zooms (must be 0); and stations "
              "named at each zoom (the mean edge on screen, px; symbols 12 px across from 75 px on). Room: the layout "
              "making room for the names left out at 75 px (tries kept / rounds run + tries for one name, unnamed there before -> after, its "
              "time).\n\n| network | request | time ms | in view | 2x | overlaps |");
  for (double e : metro::kLabelMeanEdgesPx) std::printf(" %.0f px |", e);
  std::printf(" room |\n|---|---|---:|---:|---:|---:|");
  for (std::size_t i = 0; i < metro::kLabelMeanEdgesPx.size(); ++i) std::printf("---:|");
  std::printf("---|");
  std::printf("\n");
  for (const auto& row : rows) std::fputs(row.c_str(), stdout);
}

void print_orders(const std::vector<std::string>& rows) {
  std::printf("\n## Line order along shared track\n\n"
              "pairs: line pairs sharing an edge (the model's variables); crossings: of the heuristic start and of "
              "the order served; bound: crossings no order goes below; separations: lines running on together that "
              "stop being neighbours.\n\n"
              "| network | request | pairs | time ms | heuristic crossings | crossings | bound | separations | method |\n"
              "|---|---|---:|---:|---:|---:|---:|---:|---|\n");
  for (const auto& row : rows) std::fputs(row.c_str(), stdout);
}

void print_stages(const std::vector<std::string>& rows) {
  std::printf("\n## Where the time goes (ms, wall)\n\n"
              "route: octilinear grid routing (the attempt kept, rip-ups); attempts: each routing attempt's time, and "
              "whether it left a chain unrouted or added a crossing or order violation; bends: bend reduction (rounds); "
              "spacing: the spacing LP (rounds, status); measure: the quality report; after: MIP (if any) and the tool's "
              "metrics; warp: the geographic frame.\n\n"
              "| network | request | total | visual worth | prelayout | route | attempts | bends | spacing | measure | after "
              "| warp |\n"
              "|---|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|\n");
  for (const auto& row : rows) std::fputs(row.c_str(), stdout);
}

// One table over the variants of every manifest network (and Lisbon as it is: no octi figure).
int run_variants(const nlohmann::json& manifest, const std::string& data_dir, const std::string& only_city,
                 double time_limit_s, const std::string& layouts_dir) {
  std::printf("# tourmap metro layouts on networks it has not seen\n\n"
              "Default request (lengths=visual-worth, solver=fast). holds: 0 added crossings, 0 order violations, "
              "100 %% octilinear, every input edge kept, min gap >= 0.5 mean edge, and the time within the default "
              "request's budget (300 ms under 200 stations, 2 s above).\n\n"
              "| network | variant | stations | edges | time ms | bends | displacement %% | min gap / mean edge | added "
              "crossings | order violations | edges kept | octilinear %% | holds |\n"
              "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---|\n");
  int failures = 0;
  std::uint32_t seed = 1;
  std::vector<std::string> stage_rows;
  for (const auto& entry : manifest.at("cities")) {
    const auto id = entry.at("id").get<std::string>();
    if (!entry.contains("metro") || (!only_city.empty() && only_city != id)) continue;
    auto city = load_city(entry, data_dir);
    auto cases = bench::variants_of(city.net, seed++);
    if (id == "lisbon") cases.insert(cases.begin(), {"as is", city.net});
    for (const auto& [name, net] : cases) {
      auto in = metro::make_city_metro_input(net, city.pois, geo::projection_for(model::bbox_of(net)));
      std::vector<bool> is_station;
      for (const auto& n : net.nodes) is_station.push_back(n.is_station());
      metro::CityLayoutParams params;
      params.solver = metro::LayoutSolver::fast;
      params.time_limit_s = time_limit_s;
      auto r = metro::layout_city(in, city.pois, params);
      auto m = metro::metro_compare_metrics(in.graph, is_station, in_frame(r));
      const auto& q = r.quality;
      const double budget_ms = in.station_count < 200 ? 300 : 2000;
      const bool holds = q.added_crossings == 0 && q.order_violations == 0 && m.octilinear_share == 1.0 &&
                         m.edges_kept == m.edges && q.min_station_gap_ratio >= 0.5 && r.timing.total <= budget_ms;
      failures += !holds;
      stage_rows.push_back(stage_row(id, name, r));
      if (!layouts_dir.empty()) write_layout(layouts_dir + "/" + id + "-" + name + ".json", net, in_frame(r));
      std::printf("| %s | %s | %zu | %zu | %.0f | %zu | %.2f | %.3f | %zu | %zu | %zu/%zu | %.1f | %s |\n", id.c_str(),
                  name.c_str(), in.station_count, net.edges.size(), r.timing.total, m.bends, 100 * m.displacement,
                  q.min_station_gap_ratio, q.added_crossings, q.order_violations, m.edges_kept, m.edges,
                  100 * m.octilinear_share, holds ? "yes" : "**no**");
      std::fflush(stdout);
    }
  }
  print_stages(stage_rows);
  std::printf("\n%d variant(s) where an invariant or the time budget does not hold\n", failures);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data_dir = TOURMAP_DEFAULT_DATA_DIR;
  if (const char* env = std::getenv("TOURMAP_DATA_DIR")) data_dir = env;
  std::string only_city, layouts_dir;
  if (const char* env = std::getenv("TOURMAP_BENCH_LAYOUTS")) layouts_dir = env;
  bool with_mip = false, variants = false;
  double unlabelled_at = 0;  // --unlabelled PX: list the stations without a name at that zoom
  double time_limit_s = 10.0;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    bool has_value = i + 1 < argc;
    if (arg == "--mip") with_mip = true;
    else if (arg == "--variants") variants = true;
    else if (arg == "--unlabelled" && has_value) unlabelled_at = std::stod(argv[++i]);
    else if (arg == "--data-dir" && has_value) data_dir = argv[++i];
    else if (arg == "--city" && has_value) only_city = argv[++i];
    else if (arg == "--time-limit" && has_value) time_limit_s = std::stod(argv[++i]);
    else if (arg == "--write-layouts" && has_value) layouts_dir = argv[++i];
    else {
      std::fprintf(stderr, "usage: metro_bench [--data-dir DIR] [--city ID] [--mip] [--time-limit S] [--write-layouts DIR] [--variants] [--unlabelled PX]\n");
      return 2;
    }
  }
  if (!layouts_dir.empty()) std::filesystem::create_directories(layouts_dir);
  std::vector<std::string> stage_rows;  // the second table: where each request's time went
  std::vector<std::string> order_rows;  // the third: the lines' order
  std::vector<std::string> label_rows;  // the fourth: station names
  auto manifest = nlohmann::json::parse(load::read_file(TOURMAP_MANIFEST));
  if (!layouts_dir.empty()) std::filesystem::create_directories(layouts_dir);
  if (variants) return run_variants(manifest, data_dir, only_city, time_limit_s, layouts_dir);

  struct Request {
    const char* name;
    bool worth_lengths;
    metro::LayoutSolver solver;
    bool room;  // room for names, as the server's background improvement makes it
  };
  std::vector<Request> requests = {{"default", true, metro::LayoutSolver::fast, false},
                                   {"uniform", false, metro::LayoutSolver::fast, false},
                                   {"default+room", true, metro::LayoutSolver::fast, true},
                                   {"uniform+room", false, metro::LayoutSolver::fast, true}};
  if (with_mip) {
    requests.push_back({"default+mip", true, metro::LayoutSolver::mip, true});
    requests.push_back({"uniform+mip", false, metro::LayoutSolver::mip, true});
  }

  std::printf("# tourmap metro layouts beside loom/octi\n\n"
              "default: lengths=visual-worth, uniform: lengths=uniform; solver=fast; +room: and room for names "
              "left out, as the server's background improvement makes it (+mip: also CBC in process, %.0f s limit, "
              "as the background improvement of networks up to 250 stations). Time: the layout in this process, ms; octi's: its whole process. Bends, displacement (RMS over "
              "the geographic diagonal), min/mean edge, octilinear share (of straight pieces) and input edges kept as "
              "metro_compare.py defines them; min gap / mean edge, added crossings, order violations: tourmap's "
              "quality report.\n\n",
              time_limit_s);
  std::printf("| network | request | stations | time ms | octi ms | bends | octi | displacement %% | octi | min/mean edge | octi "
              "| min gap / mean edge | added crossings | order violations | input edges kept | octilinear %% | solver |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---|\n");
  for (const auto& ref : kNetworks) {
    if (!only_city.empty() && only_city != ref.network) continue;
    const nlohmann::json* entry = nullptr;
    for (const auto& c : manifest.at("cities"))
      if (c.at("id") == ref.network) entry = &c;
    if (!entry) {
      std::fprintf(stderr, "%s: not in the manifest\n", ref.network);
      continue;
    }
    auto city = load_city(*entry, data_dir);
    // As the API derives it once per city version: the store's projection (centred on the
    // network's bbox), POI proximity to stations.
    auto in = metro::make_city_metro_input(city.net, city.pois, geo::projection_for(model::bbox_of(city.net)));
    std::vector<bool> is_station;
    for (const auto& n : city.net.nodes) is_station.push_back(n.is_station());
    for (const auto& req : requests) {
      metro::CityLayoutParams params;
      params.worth_lengths = req.worth_lengths;
      params.solver = req.solver;
      params.time_limit_s = time_limit_s;
      params.mip = [](const metro::MipModel& m, double t, double gap) { return metro::solve_with_cbc(m, t, gap); };
      params.label_room_ms = req.room ? metro::kLabelRoomCpuMs : 0.0;
      auto r = metro::layout_city(in, city.pois, params);
      auto drawn = in_frame(r);
      auto m = metro::metro_compare_metrics(in.graph, is_station, drawn);
      const auto& q = r.quality;
      std::printf("| %s | %s | %zu | %.0f | %.0f | %zu | %d | %.2f | %.2f | %.3f | %.3f | %.3f | %zu | %zu | %zu/%zu | %.1f | %s |\n",
                  ref.network, req.name, in.station_count, r.timing.total, ref.octi_s * 1000, m.bends, ref.octi_bends,
                  100 * m.displacement, ref.octi_displacement_pct, m.min_over_mean_edge, ref.octi_min_mean_edge,
                  q.min_station_gap_ratio, q.added_crossings, q.order_violations, m.edges_kept, m.edges,
                  100 * m.octilinear_share, solver_text(r.solver).c_str());
      std::fflush(stdout);
      stage_rows.push_back(stage_row(ref.network, req.name, r));
      order_rows.push_back(order_row(ref.network, req.name, r));
      label_rows.push_back(labels_row(ref.network, req.name, r, in.station_count));
      if (unlabelled_at > 0) {
        for (std::size_t k = 0; k < r.labels.size(); ++k) {
          if (metro::kLabelMeanEdgesPx[k] != unlabelled_at) continue;
          std::printf("%s %s: %zu unnamed at %.0f px, %zu with no place clear of lines and symbols; %zu names on a leader\n",
                      ref.network, req.name, r.labels[k].unlabelled, unlabelled_at, r.labels[k].no_room,
                      r.labels[k].leaders);
          std::vector<bool> has(in.names.size(), false);
          for (const auto& l : r.labels[k].labels) has[l.node] = true;
          for (std::size_t v = 0; v < in.names.size(); ++v)
            if (!in.names[v].empty() && !has[v])
              std::printf("%s %s: unnamed at %.0f px: %s\n", ref.network, req.name, metro::kLabelMeanEdgesPx[k], in.names[v].c_str());
        }
      }
      if (!layouts_dir.empty()) write_layout(layouts_dir + "/" + ref.network + "-" + req.name + ".json", city.net, drawn);
    }
  }
  print_stages(stage_rows);
  print_orders(order_rows);
  print_labels(label_rows);
  if (!layouts_dir.empty()) {
    std::printf("\nLayouts written; check one with metro_compare.py:\n\n");
    for (const auto& ref : kNetworks)
      if (only_city.empty() || only_city == ref.network)
        std::printf("    python3 ../shared/tools/metro_compare.py measure %s/%s %s/%s-default.json\n", data_dir.c_str(),
                    ref.tool_input, layouts_dir.c_str(), ref.network);
  }
  return 0;
}
