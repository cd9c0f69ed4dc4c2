// Metro map benchmark (paper 5.5): for every shared city, through the API's metro service (the
// real code path: store -> catalog -> visual worth -> layout -> warp -> clusters):
//   1. stations, edges, POIs; time by stage (visual worth, fast layout, MIP polish, warp,
//      cluster tree); the MIP's status and gap; the quality report; for the default request
//      (visual-worth lengths, solver auto) and for the fast path alone;
//   2. the largest network (London) with each solver;
//   3. active cluster queries per city: p50/p99 over random windows (in process).
// The MIP runs in process here (the server runs it in a child process it can kill).
//
//   build/bench/metro_bench [--data-dir DIR] [--city ID]   (--city: that city's layouts only)

#include "api/catalog.hpp"
#include "api/metro_service.hpp"
#include "load/file.hpp"
#include "store/manifest.hpp"
#include "store/migrate.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <unistd.h>

namespace {

using namespace tourmap;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[std::min(v.size() - 1, static_cast<std::size_t>(q * v.size()))];
}

nlohmann::json layout(api::MetroService& metro, const std::string& city, const std::string& query, double* wall_ms) {
  api::Request req;
  req.method = "GET";
  req.params["id"] = city;
  std::size_t start = 0;
  while (start < query.size()) {
    auto amp = query.find('&', start);
    auto pair = query.substr(start, amp == std::string::npos ? std::string::npos : amp - start);
    auto eq = pair.find('=');
    req.query[pair.substr(0, eq)] = pair.substr(eq + 1);
    if (amp == std::string::npos) break;
    start = amp + 1;
  }
  auto t = Clock::now();
  auto resp = metro.layout(req, false);
  *wall_ms = ms_since(t);
  return nlohmann::json::parse(resp.body);
}

void row(const std::string& city, const nlohmann::json& l, double wall, double cluster_ms) {
  const auto& q = l["quality"];
  const auto& s = l["solver"];
  const auto& mip = s.contains("mip") ? s["mip"] : nlohmann::json::object();
  std::string mip_text = mip.empty() ? "-"
                                     : mip["status"].get<std::string>() +
                                           (mip.contains("accepted") ? (mip["accepted"].get<bool>() ? ", kept" : ", not kept") : "") +
                                           (mip.contains("gap") ? ", gap " + std::to_string(mip["gap"].get<double>()).substr(0, 5) : "");
  std::printf("| %s | %zu | %zu | %zu | %.1f | %.1f (%.0f) | %s | %.1f | %.1f | %.1f | %s | %.0f%% | %d (%d, %d) | %d | %d | %.1f / %.1f |\n",
              city.c_str(), l["stations"]["features"].size(), l["edges"]["features"].size(), l["pois"]["features"].size(),
              l["timing_ms"]["visual_worth"].get<double>(), l["fast_path"]["time_ms"].get<double>(),
              l["fast_path"]["prelayout_ms"].get<double>(), mip_text.c_str(),
              mip.contains("time_ms") ? mip["time_ms"].get<double>() : 0.0, l["timing_ms"]["warp"].get<double>(), cluster_ms,
              (s["kind"].get<std::string>() + " " + s["status"].get<std::string>()).c_str(),
              100 * q["octilinear_share"].get<double>(), q["crossings"].get<int>(), q["geo_crossings"].get<int>(), q["added_crossings"].get<int>(),
              q["order_violations"].get<int>(), q["bends"].get<int>(), q["min_edge"].get<double>(), q["mean_edge"].get<double>());
  (void)wall;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data_dir = TOURMAP_DEFAULT_DATA_DIR;
  if (const char* env = std::getenv("TOURMAP_DATA_DIR")) data_dir = env;
  std::string only_city;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--data-dir") data_dir = argv[i + 1];
    if (std::string(argv[i]) == "--city") only_city = argv[i + 1];
  }

  auto dir = std::filesystem::temp_directory_path() / ("tourmap-metro-bench-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  auto db_path = (dir / "bench.db").string();
  auto manifest = store::parse_manifest(load::read_file(TOURMAP_MANIFEST), data_dir);
  manifest.roads.clear();
  {
    store::Db db(db_path);
    store::migrate(db);
    store::run_manifest(db, manifest, false, nullptr);
  }
  store::DbPool pool(db_path);
  api::Catalog catalog(pool);
  // Every section measures computations, not the store's result cache.
  auto purge = [&] {
    auto db = pool.acquire();
    store::cache_purge(*db);
  };

  std::printf("# tourmap metro benchmark\n\nLayout units: l_const = 10. Times in ms, one run each on this machine "
              "(first computation; the service caches results). MIP: CBC in process.\n");
  for (std::string query : {std::string("lengths=visual-worth&solver=auto"), std::string("lengths=visual-worth&solver=fast")}) {
    purge();
    api::MetroService metro(catalog);  // fresh caches
    std::printf("\n### Layout per city: %s\n\n", query.c_str());
    std::printf("| city | stations | edges | POIs | visual worth | fast layout (pre-layout) | MIP | MIP ms | warp | cluster tree | result | octilinear | crossings (geo, added) | order violations | bends | min / mean edge |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---|---:|---:|---:|---:|---:|\n");
    for (const auto& m : manifest.metros) {
      if (!only_city.empty() && m.city.id != only_city) continue;
      double wall = 0;
      auto l = layout(metro, m.city.id, query, &wall);
      // The layout-space cluster tree: built on the first clusters request.
      double cluster_ms = 0;
      if (!l["pois"]["features"].empty()) {
        api::Request req;
        req.params["id"] = m.city.id;
        req.query = {{"space", "layout"}, {"bbox", "-1e9,-1e9,1e9,1e9"}};
        auto eq = query.find('&');
        req.query["lengths"] = query.substr(8, eq - 8);
        req.query["solver"] = query.substr(query.find("solver=") + 7);
        auto t = Clock::now();
        metro.clusters(req);
        cluster_ms = ms_since(t);
      }
      row(m.city.id, l, wall, cluster_ms);
    }
  }

  if (!only_city.empty() && only_city != "london") {
    std::filesystem::remove_all(dir);
    return 0;
  }
  std::printf("\n### The largest network: London (302 stations) by solver\n\n");
  std::printf("| solver | total ms | result | MIP | octilinear | crossings (geo, added) | order violations | bends | fast path ripups / crossing routes / overlapping / attempt |\n");
  std::printf("|---|---:|---|---|---:|---:|---:|---:|---:|\n");
  for (std::string solver : {"fast", "auto", "mip"}) {
    purge();
    api::MetroService metro(catalog);
    double wall = 0;
    auto l = layout(metro, "london", "solver=" + solver + "&time_limit_s=10", &wall);
    const auto& q = l["quality"];
    std::string mip = l["solver"].contains("mip") ? l["solver"]["mip"].value("status", "") + " " +
                                                        l["solver"]["mip"].value("reason", "")
                                                  : "-";
    std::printf("| %s | %.0f | %s %s | %s | %.0f%% | %d (%d, %d) | %d | %d | %d / %d / %d / %d |\n", solver.c_str(), wall,
                l["solver"]["kind"].get<std::string>().c_str(), l["solver"]["status"].get<std::string>().c_str(), mip.c_str(),
                100 * q["octilinear_share"].get<double>(), q["crossings"].get<int>(), q["geo_crossings"].get<int>(), q["added_crossings"].get<int>(),
                q["order_violations"].get<int>(), q["bends"].get<int>(), l["fast_path"]["ripups"].get<int>(),
                l["fast_path"]["crossing_routes"].get<int>(), l["fast_path"]["overlapping"].get<int>(),
                l["fast_path"]["attempt"].get<int>());
  }

  if (!only_city.empty()) {
    std::filesystem::remove_all(dir);
    return 0;
  }
  std::printf("\n### Active cluster queries (geo space, in process, 2000 random windows per city)\n\n");
  std::printf("| city | POIs | tree build ms | p50 ms | p99 ms | max ms |\n|---|---:|---:|---:|---:|---:|\n");
  purge();
  api::MetroService metro(catalog);
  std::mt19937 rng(11);
  for (const auto& p : manifest.pois) {
    auto city = catalog.city(p.city_id);
    auto box = city->info.poi_bbox;
    api::Request first;
    first.params["id"] = p.city_id;
    auto t = Clock::now();
    metro.clusters(first);
    double build = ms_since(t);
    std::vector<double> times;
    std::uniform_real_distribution<double> u(0, 1), size(0.02, 1.0);
    for (int i = 0; i < 2000; ++i) {
      double w = size(rng) * (box.max_lon - box.min_lon), h = w * 0.6;
      double x = box.min_lon + u(rng) * (box.max_lon - box.min_lon - w), y = box.min_lat + u(rng) * std::max(0.0, box.max_lat - box.min_lat - h);
      api::Request req;
      req.params["id"] = p.city_id;
      char bbox[128];
      std::snprintf(bbox, sizeof bbox, "%.6f,%.6f,%.6f,%.6f", x, y, x + w, y + h);
      req.query["bbox"] = bbox;
      auto q0 = Clock::now();
      metro.clusters(req);
      times.push_back(ms_since(q0));
    }
    std::printf("| %s | %zu | %.1f | %.3f | %.3f | %.3f |\n", p.city_id.c_str(), city->pois.size(), build,
                percentile(times, 0.5), percentile(times, 0.99), *std::max_element(times.begin(), times.end()));
  }
  std::filesystem::remove_all(dir);
  return 0;
}
