// POI cluster benchmark (paper 5.4.4) on GeoNames populated places (cities1000, population as
// visual worth), with tables for:
//   1. the cycle cover: dense Hungarian vs sparse shortest paths on the kNN graph, time and cost;
//   2. building the cluster tree: time, nodes, depth, rounds, memory, serialized size;
//   3. active-cluster queries over random windows from the whole extent down to 300 m;
//   4. side by side with mapbox/supercluster 9.1.0 (issue 19) on the 10K, 138K and 1M sets.
// Data sets: the 120 most populous places of one country (the paper's size), a random 10K
// sample, all 138K places, and 1M synthetic points (every place spawns ~7 jittered points).
//
// The supercluster comparison writes the very points and windows of tables 2 and 3, turned back
// into lng/lat by the exact inverse of the set's projection, to a temp dir and runs
// `node bench/supercluster_run.mjs DIR` on them (web/node_modules/supercluster, run with its
// defaults: radius 40, extent 512, maxZoom 16, minPoints 2). A window is asked at the zoom where
// it would fill a 1024-px-wide screen: z = floor(log2(1024 / 256 * 360 / lngSpan)) clamped to
// [0, 17]; supercluster has no "fit the window" query, so this is the zoom a map showing that
// window would ask for. Quality, computed by one function for both: the mean distance from each
// point to the centroid of its cluster's points, for supercluster's partition at a zoom and for
// the cut of our tree with about as many clusters (undo merges newest first until >= C).
// Skipped with a printed line when node or web/node_modules/supercluster is missing.
//
//   build/bench/cluster_bench [--data-dir DIR] [--quick] [--country CC] [--no-supercluster]

#include "poi/active_clusters.hpp"
#include "poi/assignment.hpp"
#include "poi/cluster_tree.hpp"
#include "poi/cluster_update.hpp"
#include "poi/serialize.hpp"
#include "process_memory.hpp"

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace tourmap;
using namespace tourmap::poi;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

double peak_rss_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

struct Place {
  double lon = 0, lat = 0, population = 0;
  std::string country;
};

// GeoNames TSV: 4 latitude, 5 longitude, 8 country code, 14 population.
std::vector<Place> load_places(const std::string& path) {
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error("cannot open " + path);
  std::vector<Place> out;
  std::vector<char> buf(1 << 16);
  while (gzgets(f, buf.data(), static_cast<int>(buf.size()))) {
    std::vector<std::string> cols(1);
    for (const char* c = buf.data(); *c && *c != '\n'; ++c) {
      if (*c == '\t')
        cols.emplace_back();
      else
        cols.back().push_back(*c);
    }
    if (cols.size() < 15) continue;
    out.push_back({std::atof(cols[5].c_str()), std::atof(cols[4].c_str()), std::atof(cols[14].c_str()), cols[8]});
  }
  gzclose(f);
  return out;
}

// Equirectangular metres around the data's centre: planar enough for clustering a benchmark.
struct Projector {
  static constexpr double kR = 6371008.8, kDeg = std::numbers::pi / 180.0;
  double lon0 = 0, lat0 = 0;
  geo::XY operator()(double lon, double lat) const {
    return {kR * (lon - lon0) * kDeg * std::cos(lat0 * kDeg), kR * (lat - lat0) * kDeg};
  }
  // The exact inverse, lng/lat in degrees as x/y (not clamped: metres past the poles or the
  // antimeridian give latitudes past +-90 or longitudes past +-180).
  geo::XY inverse(geo::XY m) const {
    return {lon0 + m.x / (kR * kDeg * std::cos(lat0 * kDeg)), lat0 + m.y / (kR * kDeg)};
  }
};

Projector projector_for(const std::vector<Place>& places) {
  double lon = 0, lat = 0;
  for (const auto& p : places) {
    lon += p.lon;
    lat += p.lat;
  }
  return {lon / static_cast<double>(places.size()), lat / static_cast<double>(places.size())};
}

std::vector<ClusterPoint> to_points(const std::vector<Place>& places, const Projector& proj) {
  std::vector<ClusterPoint> out;
  for (const auto& p : places) out.push_back({proj(p.lon, p.lat), p.population});
  return out;
}

std::vector<Place> top_of_country(const std::vector<Place>& all, const std::string& cc, std::size_t n) {
  std::vector<Place> out;
  for (const auto& p : all)
    if (p.country == cc) out.push_back(p);
  std::stable_sort(out.begin(), out.end(), [](const Place& a, const Place& b) { return a.population > b.population; });
  if (out.size() > n) out.resize(n);
  return out;
}

std::vector<Place> sample(const std::vector<Place>& all, std::size_t n, unsigned seed) {
  std::vector<Place> out;
  std::mt19937 rng(seed);
  std::sample(all.begin(), all.end(), std::back_inserter(out), n, rng);
  return out;
}

// 1M synthetic POIs from the real distribution: each place spawns ~7 points, jittered by a
// normal of sigma 0.5..10 km growing with its population, worth = its population / 7 times a
// log-normal factor.
std::vector<ClusterPoint> synthetic(const std::vector<Place>& all, std::size_t n, unsigned seed,
                                    const Projector& proj) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<ClusterPoint> out;
  out.reserve(n);
  const double per_place = static_cast<double>(n) / static_cast<double>(all.size());
  double owed = 0;
  for (const auto& p : all) {
    owed += per_place;
    const geo::XY c = proj(p.lon, p.lat);
    const double sigma = std::clamp(2000.0 * std::sqrt(std::max(p.population, 1.0) / 1e5), 500.0, 10000.0);
    for (; owed >= 1 && out.size() < n; owed -= 1)
      out.push_back(
          {{c.x + sigma * normal(rng), c.y + sigma * normal(rng)}, p.population / 7.0 * std::exp(normal(rng))});
  }
  return out;
}

std::vector<geo::XY> positions(const std::vector<ClusterPoint>& p) {
  std::vector<geo::XY> out;
  for (const auto& q : p) out.push_back(q.pos);
  return out;
}

void print_assignment(const std::vector<std::pair<std::string, std::vector<ClusterPoint>>>& sets) {
  std::printf("\n## Cycle cover: dense Hungarian vs sparse shortest paths on the symmetric kNN graph\n\n");
  std::printf(
      "| points | n | dense ms | dense cost km | sparse k | sparse ms | sparse cost km | cost vs dense | self-loops "
      "|\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& [name, set] : sets) {
    auto pts = positions(set);
    auto t0 = Clock::now();
    auto dense = min_cycle_cover_dense(pts);
    double dense_ms = ms_since(t0);
    for (std::size_t k : {std::size_t{4}, std::size_t{8}, std::size_t{16}, pts.size() - 1}) {
      if (k > pts.size() - 1) continue;
      t0 = Clock::now();
      auto sparse = min_cycle_cover_sparse(pts, k);
      double sparse_ms = ms_since(t0);
      std::printf("| %s | %zu | %.1f | %.1f | %zu | %.1f | %.1f | %+.4f%% | %zu |\n", name.c_str(), pts.size(),
                  dense_ms, dense.cost / 1000, k, sparse_ms, sparse.cost / 1000,
                  100.0 * (sparse.cost / dense.cost - 1.0), sparse.self_loops);
    }
  }
}

struct Built {
  std::string name;
  std::vector<ClusterPoint> points;
  Projector proj;  // the one that made `points`
  ClusterTree tree;
  // Filled by print_build_row and print_queries, for the side-by-side table.
  double build_ms = 0, peak_growth_mib = 0, process_peak_mib = 0;
  bool peak_from_hwm = false;  // VmHWM after a reset; else growth of getrusage's lifetime peak
  double query_p50_ms = 0, query_p99_ms = 0, active_p50 = 0;
};

// A set from real places, projected around its own centre.
Built make_set(std::string name, const std::vector<Place>& places) {
  Built b;
  b.name = std::move(name);
  b.proj = projector_for(places);
  b.points = to_points(places, b.proj);
  return b;
}

void print_build_row(Built& b, const ClusterOptions& options) {
  // Peak growth over the build: VmHWM reset to the current RSS first (Linux >= 4.0). The reset
  // also lowers getrusage's peak, so the last column is the peak since this build started.
  malloc_trim(0);  // hand freed heap back first, or its reuse would hide the build's growth
  const double rss_before = bench::status_mb("VmRSS:"), lifetime_before = peak_rss_mib();
  b.peak_from_hwm = bench::reset_peak() && rss_before > 0;
  auto t0 = Clock::now();
  b.tree = build_cluster_tree(b.points, options);
  double build_ms = ms_since(t0);
  const double rss = peak_rss_mib();  // before serializing: the sets come smallest first
  b.build_ms = build_ms;
  b.process_peak_mib = rss;
  b.peak_growth_mib = b.peak_from_hwm ? bench::status_mb("VmHWM:") - rss_before : rss - lifetime_before;
  const auto& t = b.tree;
  // Depth of every node: parents are made after their children, so walk down from the root.
  std::vector<std::uint32_t> depth(t.nodes.size(), 0);
  std::uint32_t max_depth = 0, max_fanout = 0;
  for (std::size_t i = t.nodes.size(); i-- > 0;) {
    const auto& c = t.nodes[i];
    if (c.parent >= 0) depth[i] = depth[static_cast<std::size_t>(c.parent)] + 1;
    max_depth = std::max(max_depth, depth[i]);
    max_fanout = std::max(max_fanout, c.child_count);
  }
  double mean_leaf_depth = 0;
  for (std::size_t i = 0; i < t.leaves; ++i) mean_leaf_depth += depth[i];
  mean_leaf_depth /= static_cast<double>(std::max<std::size_t>(t.leaves, 1));
  t0 = Clock::now();
  std::string bytes = serialize(t);
  double ser_ms = ms_since(t0);
  t0 = Clock::now();
  ClusterTree back = deserialize(bytes);
  double de_ms = ms_since(t0);
  double mib = static_cast<double>(t.nodes.size() * sizeof(ClusterNode) + t.children.size() * 4) / (1 << 20);
  std::printf("| %s | %zu | %.0f | %zu | %u | %u | %.1f | %u | %.1f | %.1f | %.0f / %.0f | %.0f |\n", b.name.c_str(),
              t.leaves, build_ms, t.nodes.size(), t.nodes[t.root].level, max_depth, mean_leaf_depth, max_fanout, mib,
              static_cast<double>(bytes.size()) / (1 << 20), ser_ms, de_ms, rss);
  std::fflush(stdout);
}

struct Window {
  geo::XY lo, hi;
  double side = 0;  // before the aspect
};

std::vector<Window> make_windows(const Built& b, std::size_t windows, unsigned seed) {
  const auto& t = b.tree;
  const auto& root = t.nodes[t.root];
  const double extent = std::max(root.max.x - root.min.x, root.max.y - root.min.y);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, b.points.size() - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Window> out;
  for (std::size_t q = 0; q < windows; ++q) {
    // Side log-uniform in [300 m, extent], aspect 0.5..2, centred near a random POI.
    const double side = 300.0 * std::pow(std::max(extent, 301.0) / 300.0, u(rng));
    const double aspect = std::pow(2.0, 2 * u(rng) - 1);
    const geo::XY c = b.points[pick(rng)].pos;
    const double w = side * std::sqrt(aspect), h = side / std::sqrt(aspect);
    const geo::XY lo{c.x - w * u(rng), c.y - h * u(rng)};
    out.push_back({lo, {lo.x + w, lo.y + h}, side});
  }
  return out;
}

void print_queries(Built& b, const std::vector<Window>& windows) {
  const auto& t = b.tree;
  std::vector<double> ms, actives;
  std::vector<double> by_size[3];  // < 10 km, < 500 km, larger
  // One untimed pass first, as supercluster_run.mjs does for its JIT: the same warm caches for
  // both (a first pass right after serializing a 140 MiB tree measured 3x slower at p99).
  std::size_t warm = 0;
  for (const auto& [lo, hi, side] : windows) warm += active_clusters(t, lo, hi, 10, 20).active;
  if (warm == 0) std::printf("(no window holds an active cluster)\n");
  for (const auto& [lo, hi, side] : windows) {
    auto t0 = Clock::now();
    auto r = active_clusters(t, lo, hi, 10, 20);  // as the API asks: M = 10, at least 2M active
    double dt = ms_since(t0);
    ms.push_back(dt);
    actives.push_back(static_cast<double>(r.active));
    by_size[side < 1e4 ? 0 : side < 5e5 ? 1 : 2].push_back(dt);
  }
  b.query_p50_ms = percentile(ms, 0.5);
  b.query_p99_ms = percentile(ms, 0.99);
  b.active_p50 = percentile(actives, 0.5);
  std::printf("| %s | %zu | %.3f | %.3f | %.3f | %.3f / %.3f / %.3f | %.0f | %.0f | %.0f |\n", b.name.c_str(), t.leaves,
              percentile(ms, 0.5), percentile(ms, 0.99), percentile(ms, 1.0), percentile(by_size[0], 0.99),
              percentile(by_size[1], 0.99), percentile(by_size[2], 0.99), percentile(actives, 0.5),
              percentile(actives, 0.99), percentile(actives, 1.0));
  std::fflush(stdout);
}


// ---- Side by side with supercluster (issue 19) ----

// The quality figure, one function for both hierarchies: the mean distance in km (planar metres
// of `points`) from each point to the centroid of its cluster's points. label[i] in 0..clusters-1.
double mean_centroid_distance_km(const std::vector<ClusterPoint>& points, const std::vector<std::int32_t>& label,
                                 std::size_t clusters) {
  std::vector<geo::XY> sum(clusters, geo::XY{0, 0});
  std::vector<std::size_t> count(clusters, 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto c = static_cast<std::size_t>(label[i]);
    sum[c].x += points[i].pos.x;
    sum[c].y += points[i].pos.y;
    ++count[c];
  }
  double total = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto c = static_cast<std::size_t>(label[i]);
    const double n = static_cast<double>(count[c]);
    total += std::hypot(points[i].pos.x - sum[c].x / n, points[i].pos.y - sum[c].y / n);
  }
  return points.empty() ? 0.0 : total / static_cast<double>(points.size()) / 1000.0;
}

// Our partition with at least `want` clusters: from {root}, undo merges newest first. Nodes are
// in creation order and parents come after children, so after undoing every node above index j
// the clusters are the nodes <= j whose parent is > j. Returns the labels; `clusters` gets C.
std::vector<std::int32_t> tree_cut(const ClusterTree& t, std::size_t want, std::size_t& clusters) {
  std::size_t j = t.root, count = 1;
  for (; count < want && j >= t.leaves && j > 0; --j) count += t.nodes[j].child_count - 1;
  std::vector<std::int32_t> top(j + 1), dense(j + 1, -1), label(t.leaves);
  clusters = 0;
  for (std::size_t i = j + 1; i-- > 0;) {
    const std::int32_t parent = t.nodes[i].parent;
    top[i] = parent < 0 || static_cast<std::size_t>(parent) > j ? static_cast<std::int32_t>(i) : top[parent];
    if (top[i] == static_cast<std::int32_t>(i)) dense[i] = static_cast<std::int32_t>(clusters++);
  }
  for (std::size_t i = 0; i < t.leaves; ++i) label[i] = dense[static_cast<std::size_t>(top[i])];
  return label;
}

// The same cut for a tree whose nodes are not in creation order (an updated one): undo the
// merges of the highest round first (later nodes first within a round) until >= `want`.
std::vector<std::int32_t> tree_cut_by_level(const ClusterTree& t, std::size_t want, std::size_t& clusters) {
  std::vector<std::uint32_t> inner;
  for (auto id = static_cast<std::uint32_t>(t.leaves); id < t.nodes.size(); ++id) inner.push_back(id);
  std::sort(inner.begin(), inner.end(), [&](std::uint32_t a, std::uint32_t b) {
    return t.nodes[a].level != t.nodes[b].level ? t.nodes[a].level > t.nodes[b].level : a > b;
  });
  std::vector<char> undone(t.nodes.size(), 0);
  std::size_t count = 1;
  for (std::uint32_t id : inner) {
    if (count >= want) break;
    undone[id] = 1;
    count += t.nodes[id].child_count - 1;
  }
  std::vector<std::int32_t> dense(t.nodes.size(), -1), label(t.leaves);
  clusters = 0;
  for (std::uint32_t leaf = 0; leaf < t.leaves; ++leaf) {
    std::uint32_t cut = leaf;  // the highest ancestor not undone (undone nodes form a top)
    for (std::int32_t p = t.nodes[leaf].parent; p >= 0; p = t.nodes[p].parent)
      if (!undone[p]) cut = static_cast<std::uint32_t>(p);
    if (dense[cut] < 0) dense[cut] = static_cast<std::int32_t>(clusters++);
    label[leaf] = dense[cut];
  }
  return label;
}

// ---- Incremental updates (issue 19) ----

// 1,000 edits as a day of POI writes might bring: a third removed, a third moved by ~300 m (some
// re-weighted only), a third added near existing POIs. Returns the POI list after them.
std::vector<ClusterPoint> edits_for(const std::vector<ClusterPoint>& before, std::size_t removed, std::size_t moved,
                                    std::size_t added, unsigned seed, ClusterEdits& e) {
  std::mt19937 rng(seed);
  std::vector<std::uint32_t> order(before.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  std::normal_distribution<double> step(0.0, 300.0);
  std::exponential_distribution<double> w(1.0);
  e = {};
  e.removed.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(removed));
  std::vector<ClusterPoint> now = before;
  for (std::size_t k = removed; k < removed + moved; ++k) {
    ClusterPoint p = before[order[k]];
    if (k % 4 == 0)
      p.worth *= 2;
    else
      p.pos = {p.pos.x + step(rng), p.pos.y + step(rng)};
    e.changed.emplace_back(order[k], p);
    now[order[k]] = p;
  }
  for (std::size_t k = 0; k < added; ++k) {
    const ClusterPoint& near = before[order[before.size() - 1 - k]];
    e.added.push_back({{near.pos.x + step(rng), near.pos.y + step(rng)}, near.worth * w(rng)});
  }
  std::vector<char> gone(before.size(), 0);
  for (std::uint32_t i : e.removed) gone[i] = 1;
  std::vector<ClusterPoint> after;
  for (std::uint32_t i = 0; i < before.size(); ++i)
    if (!gone[i]) after.push_back(now[i]);
  after.insert(after.end(), e.added.begin(), e.added.end());
  return after;
}

void print_updates(const Built& b, const ClusterOptions& options) {
  struct Case {
    const char* name;
    std::size_t removed, moved, added;
  };
  const Case cases[] = {{"1 added", 0, 0, 1}, {"1 moved", 0, 1, 0}, {"1 removed", 1, 0, 0}, {"1,000 mixed", 333, 333, 334}};
  for (const Case& c : cases) {
    ClusterEdits e;
    const auto after = edits_for(b.points, c.removed, c.moved, c.added, 21, e);
    // The service keeps built trees shared and read-only: it updates a copy.
    auto t0 = Clock::now();
    ClusterTree t = copy_for_update(b.tree);
    const double copy_ms = ms_since(t0);
    t0 = Clock::now();
    const ClusterUpdateStats stats = update_cluster_tree(t, e, options);
    const double update_ms = ms_since(t0);
    std::printf("| %s | %s | %.1f | %.0f | %.2f %% | %.0f | %zu | %zu | %zu | %zu |", b.name.c_str(), c.name, update_ms,
                b.build_ms, 100.0 * update_ms / b.build_ms, copy_ms, stats.inserted, stats.resolved, stats.split,
                stats.dissolved);
    if (c.added + c.moved + c.removed < 1000) {
      std::printf(" - | - |\n");
      continue;
    }
    // Quality against a rebuild of the same POIs, at three cluster counts.
    t0 = Clock::now();
    const ClusterTree rebuilt = build_cluster_tree(after, options);
    const double rebuild_ms = ms_since(t0);
    std::string quality;
    for (const std::size_t want : {after.size() / 1000, after.size() / 100, after.size() / 10}) {
      std::size_t c_inc = 0, c_new = 0;
      const auto inc_labels = tree_cut_by_level(t, want, c_inc);
      const auto new_labels = tree_cut_by_level(rebuilt, want, c_new);
      const double inc = mean_centroid_distance_km(after, inc_labels, c_inc);
      const double fresh = mean_centroid_distance_km(after, new_labels, c_new);
      char cell[96];
      std::snprintf(cell, sizeof cell, "%s%zu: %.3f / %.3f (%.3f)", quality.empty() ? "" : "; ", c_new, inc, fresh,
                    inc / fresh);
      quality += cell;
    }
    std::printf(" %.0f | %s |\n", rebuild_ms, quality.c_str());
  }
  std::fflush(stdout);
}

template <class T>
void write_array(const std::filesystem::path& path, const std::vector<T>& v) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::vector<std::int32_t> read_labels(const std::filesystem::path& path, std::size_t n) {
  std::vector<std::int32_t> v(n);
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(std::int32_t)));
  if (!in || in.gcount() != static_cast<std::streamsize>(n * sizeof(std::int32_t)))
    throw std::runtime_error("short read of " + path.string());
  return v;
}

struct SuperclusterRun {
  std::map<std::string, double> value;  // the numeric lines of result.txt
  std::string peak_how;
  std::vector<std::size_t> zoom_clusters;  // C at zoom 0..16
};

// Why the comparison cannot run, or "" when it can.
std::string supercluster_missing(const std::filesystem::path& root) {
  if (std::system("command -v node >/dev/null 2>&1") != 0) return "node is not on PATH";
  if (!std::filesystem::exists(root / "web/node_modules/supercluster/package.json"))
    return "web/node_modules/supercluster is missing (cd web && npm install)";
  if (!std::filesystem::exists(root / "bench/supercluster_run.mjs")) return "bench/supercluster_run.mjs is missing";
  return "";
}

// Writes the points and windows to `dir` in lng/lat, runs the node script, reads its results.
SuperclusterRun run_supercluster(const std::filesystem::path& root, const std::filesystem::path& dir, const Built& b,
                                 const std::vector<Window>& windows) {
  std::vector<double> pts, wins;
  pts.reserve(3 * b.points.size());
  for (const auto& p : b.points) {
    const geo::XY ll = b.proj.inverse(p.pos);
    pts.insert(pts.end(), {ll.x, ll.y, p.worth});
  }
  for (const auto& w : windows) {
    const geo::XY lo = b.proj.inverse(w.lo), hi = b.proj.inverse(w.hi);
    wins.insert(wins.end(), {lo.x, lo.y, hi.x, hi.y});
  }
  write_array(dir / "points.f64", pts);
  write_array(dir / "windows.f64", wins);
  const std::string cmd = "node --expose-gc '" + (root / "bench/supercluster_run.mjs").string() + "' '" + dir.string() + "'";
  std::fflush(stdout);
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("failed: " + cmd);
  SuperclusterRun r;
  std::ifstream in(dir / "result.txt");
  std::string key;
  while (in >> key) {
    if (key == "zoom") {
      std::size_t z = 0, c = 0;
      in >> z >> c;
      r.zoom_clusters.resize(std::max(r.zoom_clusters.size(), z + 1));
      r.zoom_clusters[z] = c;
    } else if (key == "peak_growth_how") {
      in >> r.peak_how;
    } else {
      in >> r.value[key];
    }
  }
  if (r.zoom_clusters.size() != 17 || !r.value.count("load_ms")) throw std::runtime_error("incomplete result.txt");
  return r;
}

void print_side_by_side(const std::filesystem::path& root, const Built& b, const std::vector<Window>& windows) {
  char tmpl[] = "/tmp/cluster_bench_sc_XXXXXX";
  if (!mkdtemp(tmpl)) throw std::runtime_error("mkdtemp failed");
  const std::filesystem::path dir = tmpl;
  struct Cleanup {
    std::filesystem::path dir;
    ~Cleanup() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  } cleanup{dir};
  const auto t0 = Clock::now();
  const SuperclusterRun sc = run_supercluster(root, dir, b, windows);
  std::size_t outside = 0;
  for (const auto& p : b.points) outside += std::abs(b.proj.inverse(p.pos).x) > 180.0;
  auto v = [&](const char* key) { return sc.value.at(key); };
  std::printf("\n### %s: %zu POIs, %zu windows (node run %.0f s)\n\n", b.name.c_str(), b.points.size(),
              windows.size(), ms_since(t0) / 1000);
  std::printf(
      "Same points and windows for both. supercluster: defaults, one timed load after a warm-up load of 10K points; "
      "getClusters at z = floor(log2(1024/256 * 360 / lngSpan)) clamped to [0, 17] (the zoom where the window "
      "fills a 1024-px-wide screen; bbox longitudes clamped to +-180 so nothing wraps), timed after one warm-up pass "
      "over all windows. tourmap: build_cluster_tree, active_clusters(M = 10, at least 20), timed after one warm-up pass over all windows. Peak growth: "
      "VmHWM after a reset minus RSS before, with the input already in memory (%s for supercluster, %s for "
      "tourmap).%s\n\n",
      sc.peak_how == "VmHWM" ? "VmHWM" : "lifetime maxRSS", b.peak_from_hwm ? "VmHWM" : "lifetime maxRSS",
      outside ? (" " + std::to_string(outside) + " points lie past +-180 deg (jitter): supercluster's world "
                 "queries never return them.").c_str()
              : "");
  std::printf("| %s | supercluster 9.1.0 | tourmap |\n|---|---:|---:|\n", b.name.c_str());
  std::printf("| build s | %.2f | %.2f |\n", v("load_ms") / 1000, b.build_ms / 1000);
  std::printf("| peak memory growth MiB | %.0f | %.0f |\n", v("peak_growth_mib"), b.peak_growth_mib);
  std::printf("| process peak RSS MiB | %.0f | %.0f |\n", v("process_peak_mib"), b.process_peak_mib);
  std::printf("| query p50 ms | %.4f | %.4f |\n", v("query_p50_ms"), b.query_p50_ms);
  std::printf("| query p99 ms | %.4f | %.4f |\n", v("query_p99_ms"), b.query_p99_ms);
  std::printf("| clusters returned p50 (supercluster: features; tourmap: active, of which 20 are sent) | %.0f | %.0f |\n",
              v("returned_p50"), b.active_p50);

  // Zooms whose cluster count is between 50 and n/3, distinct counts, at most 6 spread evenly.
  std::vector<std::size_t> zooms;
  for (std::size_t z = 0; z < sc.zoom_clusters.size(); ++z) {
    const std::size_t c = sc.zoom_clusters[z];
    if (c >= 50 && c <= b.points.size() / 3 && (zooms.empty() || sc.zoom_clusters[zooms.back()] != c))
      zooms.push_back(z);
  }
  if (zooms.size() > 6) {
    std::vector<std::size_t> spread;
    for (std::size_t k = 0; k < 6; ++k) spread.push_back(zooms[k * (zooms.size() - 1) / 5]);
    zooms = spread;
  }
  std::printf(
      "\nQuality at matched cluster counts: mean distance from each POI to the centroid of its cluster's POIs, "
      "planar km, LOWER IS BETTER. supercluster: its partition at the zoom; tourmap: from the root, merges undone "
      "newest first until it has >= supercluster's C clusters. Ratio < 1: tourmap's clusters are tighter.\n\n");
  std::printf(
      "| zoom | supercluster C | supercluster mean km | tourmap C | tourmap mean km | tourmap / supercluster | better "
      "|\n|---:|---:|---:|---:|---:|---:|---|\n");
  for (std::size_t z : zooms) {
    const std::size_t c = sc.zoom_clusters[z];
    const auto theirs = read_labels(dir / ("zoom_" + std::to_string(z) + ".i32"), b.points.size());
    const double their_km = mean_centroid_distance_km(b.points, theirs, c);
    std::size_t ours_c = 0;
    const auto ours = tree_cut(b.tree, c, ours_c);
    const double our_km = mean_centroid_distance_km(b.points, ours, ours_c);
    std::printf("| %zu | %zu | %.2f | %zu | %.2f | %.3f | %s |\n", z, c, their_km, ours_c, our_km, our_km / their_km,
                our_km < their_km ? "tourmap" : our_km > their_km ? "supercluster" : "tie");
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::string data_dir = TOURMAP_DEFAULT_DATA_DIR;
  if (const char* env = std::getenv("TOURMAP_DATA_DIR")) data_dir = env;
  bool quick = false, supercluster = true;
  std::string country = "DE";
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--data-dir" && i + 1 < argc) data_dir = argv[++i];
    if (a == "--country" && i + 1 < argc) country = argv[++i];
    if (a == "--quick") quick = true;
    if (a == "--no-supercluster") supercluster = false;
  }
  auto t0 = Clock::now();
  const auto places = load_places(data_dir + "/points/geonames_cities1000.txt.gz");
  std::printf(
      "# tourmap POI cluster benchmark\n\nGeoNames cities1000: %zu places loaded in %.0f ms; population "
      "as visual worth; equirectangular metres. Single thread.\n",
      places.size(), ms_since(t0));

  print_assignment({{country + " top 120", make_set("", top_of_country(places, country, 120)).points},
                    {country + " top 500", make_set("", top_of_country(places, country, 500)).points},
                    {"world sample 500", make_set("", sample(places, 500, 1)).points},
                    {"world sample 1000", make_set("", sample(places, 1000, 2)).points}});

  std::vector<Built> sets;
  sets.push_back(make_set(country + " top 120", top_of_country(places, country, 120)));
  sets.push_back(make_set("world sample 10K", sample(places, 10000, 3)));
  sets.push_back(make_set("world all", places));
  if (!quick) {
    Built b;
    b.name = "synthetic 1M";
    b.proj = projector_for(places);
    b.points = synthetic(places, 1000000, 4, b.proj);
    sets.push_back(std::move(b));
  }

  ClusterOptions options;
  std::printf("\n## Building the cluster tree (dense_limit %zu, k %zu, candidates symmetric)\n\n", options.dense_limit,
              options.k);
  std::printf(
      "| points | POIs | build ms | nodes | rounds | max depth | mean leaf depth | max fan-out | tree MiB | "
      "serialized MiB | serialize / deserialize ms | peak RSS MiB after build |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (auto& b : sets) print_build_row(b, options);

  const std::size_t windows = quick ? 1000 : 5000;
  std::printf(
      "\n## Active clusters, M = 10, refined to at least 20 as the API does (%zu random windows per set: side log-uniform 300 m .. extent, aspect "
      "0.5..2, around a random POI; timed after one untimed pass)\n\n",
      windows);
  std::printf(
      "| points | POIs | p50 ms | p99 ms | max ms | p99 ms by side <10 km / <500 km / larger | active p50 | "
      "active p99 | active max |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::vector<std::vector<Window>> set_windows;
  for (auto& b : sets) {
    set_windows.push_back(make_windows(b, windows, 11));
    print_queries(b, set_windows.back());
  }

  std::printf(
      "\n## Incremental updates (issue 19): edits applied to the built tree in place, against its build time; "
      "quality = mean km from each POI to its cluster's centroid at about C clusters, updated / rebuilt "
      "(ratio; < 1: the update clusters tighter)\n\n");
  std::printf(
      "| points | edits | update ms | build ms | update / build | copy of the tree ms | inserted | covers re-solved | "
      "splits | dissolved | rebuild ms | quality at C: updated / rebuilt (ratio) |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
  for (const auto& b : sets)
    if (b.points.size() >= 100000) print_updates(b, options);

  std::printf("\n## Side by side with mapbox/supercluster 9.1.0 (issue 19)\n");
  const std::filesystem::path root = TOURMAP_SOURCE_DIR;
  const std::string missing = supercluster ? supercluster_missing(root) : "--no-supercluster given";
  if (!missing.empty()) {
    std::printf("\nSkipped: %s.\n", missing.c_str());
    return 0;
  }
  for (std::size_t i = 1; i < sets.size(); ++i) print_side_by_side(root, sets[i], set_windows[i]);  // not the 120
  return 0;
}
