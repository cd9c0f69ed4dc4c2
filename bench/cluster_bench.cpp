// POI cluster benchmark (paper 5.4.4) on GeoNames populated places (cities1000, population as
// visual worth), with tables for:
//   1. the cycle cover: dense Hungarian vs sparse shortest paths on the kNN graph, time and cost;
//   2. building the cluster tree: time, nodes, depth, rounds, memory, serialized size;
//   3. active-cluster queries over random windows from the whole extent down to 300 m.
// Data sets: the 120 most populous places of one country (the paper's size), a random 10K
// sample, all 138K places, and 1M synthetic points (every place spawns ~7 jittered points).
//
//   build/bench/cluster_bench [--data-dir DIR] [--quick] [--country CC]

#include "poi/active_clusters.hpp"
#include "poi/assignment.hpp"
#include "poi/cluster_tree.hpp"
#include "poi/serialize.hpp"

#include <sys/resource.h>
#include <zlib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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
  double lon0 = 0, lat0 = 0;
  geo::XY operator()(double lon, double lat) const {
    constexpr double kR = 6371008.8, kDeg = std::numbers::pi / 180.0;
    return {kR * (lon - lon0) * kDeg * std::cos(lat0 * kDeg), kR * (lat - lat0) * kDeg};
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

std::vector<ClusterPoint> to_points(const std::vector<Place>& places) {
  Projector proj = projector_for(places);
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
std::vector<ClusterPoint> synthetic(const std::vector<Place>& all, std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Projector proj = projector_for(all);
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
  ClusterTree tree;
};

void print_build_row(Built& b, const ClusterOptions& options) {
  auto t0 = Clock::now();
  b.tree = build_cluster_tree(b.points, options);
  double build_ms = ms_since(t0);
  const double rss = peak_rss_mib();  // before serializing: the sets come smallest first
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

void print_queries(const Built& b, std::size_t windows, unsigned seed) {
  const auto& t = b.tree;
  const auto& root = t.nodes[t.root];
  const double extent = std::max(root.max.x - root.min.x, root.max.y - root.min.y);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, b.points.size() - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> ms, actives;
  std::vector<double> by_size[3];  // < 10 km, < 500 km, larger
  for (std::size_t q = 0; q < windows; ++q) {
    // Side log-uniform in [300 m, extent], aspect 0.5..2, centred near a random POI.
    const double side = 300.0 * std::pow(std::max(extent, 301.0) / 300.0, u(rng));
    const double aspect = std::pow(2.0, 2 * u(rng) - 1);
    const geo::XY c = b.points[pick(rng)].pos;
    const double w = side * std::sqrt(aspect), h = side / std::sqrt(aspect);
    const geo::XY lo{c.x - w * u(rng), c.y - h * u(rng)};
    const geo::XY hi{lo.x + w, lo.y + h};
    auto t0 = Clock::now();
    auto r = active_clusters(t, lo, hi, 10, 20);  // as the API asks: M = 10, at least 2M active
    double dt = ms_since(t0);
    ms.push_back(dt);
    actives.push_back(static_cast<double>(r.active));
    by_size[side < 1e4 ? 0 : side < 5e5 ? 1 : 2].push_back(dt);
  }
  std::printf("| %s | %zu | %.3f | %.3f | %.3f | %.3f / %.3f / %.3f | %.0f | %.0f | %.0f |\n", b.name.c_str(), t.leaves,
              percentile(ms, 0.5), percentile(ms, 0.99), percentile(ms, 1.0), percentile(by_size[0], 0.99),
              percentile(by_size[1], 0.99), percentile(by_size[2], 0.99), percentile(actives, 0.5),
              percentile(actives, 0.99), percentile(actives, 1.0));
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::string data_dir = TOURMAP_DEFAULT_DATA_DIR;
  if (const char* env = std::getenv("TOURMAP_DATA_DIR")) data_dir = env;
  bool quick = false;
  std::string country = "DE";
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--data-dir" && i + 1 < argc) data_dir = argv[++i];
    if (a == "--country" && i + 1 < argc) country = argv[++i];
    if (a == "--quick") quick = true;
  }
  auto t0 = Clock::now();
  const auto places = load_places(data_dir + "/points/geonames_cities1000.txt.gz");
  std::printf(
      "# tourmap POI cluster benchmark\n\nGeoNames cities1000: %zu places loaded in %.0f ms; population "
      "as visual worth; equirectangular metres. Single thread.\n",
      places.size(), ms_since(t0));

  print_assignment({{country + " top 120", to_points(top_of_country(places, country, 120))},
                    {country + " top 500", to_points(top_of_country(places, country, 500))},
                    {"world sample 500", to_points(sample(places, 500, 1))},
                    {"world sample 1000", to_points(sample(places, 1000, 2))}});

  std::vector<Built> sets;
  sets.push_back({country + " top 120", to_points(top_of_country(places, country, 120)), {}});
  sets.push_back({"world sample 10K", to_points(sample(places, 10000, 3)), {}});
  sets.push_back({"world all", to_points(places), {}});
  if (!quick) sets.push_back({"synthetic 1M", synthetic(places, 1000000, 4), {}});

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
      "0.5..2, around a random POI)\n\n",
      windows);
  std::printf(
      "| points | POIs | p50 ms | p99 ms | max ms | p99 ms by side <10 km / <500 km / larger | active p50 | "
      "active p99 | active max |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& b : sets) print_queries(b, windows, 11);
  return 0;
}
