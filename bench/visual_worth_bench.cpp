// Visual worth benchmark (paper 5.4.1, core/metro/visual_worth.hpp): the batched evaluation
// (at_points / the raster) against the old per-point at() loop, for
//   * the shared cities with POIs (the project's loaders, scripts/sample-data.json; the
//     endpoint's raster: cell centres of the city's lon/lat bbox, projected), as they come
//     (their work is within the budget: exact) and forced onto the approximation;
//   * synthetic cities of 10K, 100K and 1M POIs over 30 x 30 km (a dense centre, hot spots,
//     a sparse spread; ranks in random order, distance to 150 synthetic stations).
// Per set: a 512 x 512 raster and the worth of every POI. The exact loop runs on a subset of
// the points when the whole would sum more than ~2e8 kernels: its time is that subset's,
// scaled to all points ("~"), and the errors are measured on that subset (relative error where
// the exact value is at least 1e-3 of the maximum; the largest error as a share of the
// maximum, the raster's unit). Times are one run each on this machine, single-threaded.
//
//   build/bench/visual_worth_bench [--data-dir DIR] [--max-pois N]

#include "api/metro_data.hpp"
#include "load/file.hpp"
#include "load/metro_load.hpp"
#include "load/poi_load.hpp"
#include "store/manifest.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

namespace {

using namespace tourmap;
using Clock = std::chrono::steady_clock;
using metro::XY;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

struct Case {
  std::string data;
  std::size_t pois = 0;
  std::string query;
  std::vector<XY> points;
};

void row(const metro::VisualWorth& vw, const Case& c, const metro::WorthEvalOptions& options) {
  // The new path, timed first (it builds no R-tree; the exact loop below builds it).
  metro::WorthEvalReport report;
  auto t = Clock::now();
  auto fast = vw.at_points(c.points, options, &report);
  const double fast_ms = ms_since(t);

  // The old loop on a strided subset when the whole would be long.
  const std::size_t q = c.points.size();
  const double per_point = report.estimated_work / static_cast<double>(q);
  std::size_t m = q;
  if (report.estimated_work > 2e8) m = std::max<std::size_t>(400, static_cast<std::size_t>(2e8 / std::max(per_point, 1.0)));
  m = std::min(m, q);
  const std::size_t stride = q / m;
  vw.at({0, 0});  // builds the R-tree outside the timing (the old constructor built it)
  std::vector<std::pair<std::size_t, double>> exact;
  t = Clock::now();
  for (std::size_t k = 0; k < q; k += stride) exact.push_back({k, vw.at(c.points[k])});
  double exact_ms = ms_since(t) * static_cast<double>(q) / static_cast<double>(exact.size());
  const bool scaled = exact.size() < q;

  double max_exact = 0;
  for (const auto& e : exact) max_exact = std::max(max_exact, e.second);
  double max_rel = 0, mean_rel = 0, max_abs = 0;
  std::size_t counted = 0;
  for (const auto& [k, e] : exact) {
    const double err = std::fabs(fast[k] - e);
    if (max_exact > 0) max_abs = std::max(max_abs, err / max_exact);
    if (e > 0 && e >= 1e-3 * max_exact) {
      max_rel = std::max(max_rel, err / e);
      mean_rel += err / e;
      ++counted;
    }
  }
  if (counted) mean_rel /= static_cast<double>(counted);
  char path[96];
  if (report.exact)
    std::snprintf(path, sizeof path, "exact");
  else
    std::snprintf(path, sizeof path, "approx: %zu exact POIs, %zu levels, %zu tiles", report.exact_sources, report.levels,
                  report.tiles);
  std::printf("| %s | %zu | %s | %zu | %.3g | %s%.0f | %.1f | %.0fx | %s | %zu | %.2f%% | %.3f%% | %.3f%% |\n", c.data.c_str(),
              c.pois, c.query.c_str(), q, report.estimated_work, scaled ? "~" : "", exact_ms, fast_ms,
              exact_ms / std::max(fast_ms, 1e-3), path, exact.size(), 100 * max_rel, 100 * mean_rel, 100 * max_abs);
  std::fflush(stdout);
}

void header() {
  std::printf("| data | POIs | query | points | est. kernels | old at() loop ms | new ms | speed-up | new path | "
              "points checked | max rel. err | mean rel. err | max err / max |\n");
  std::printf("|---|---:|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|\n");
}

// The endpoint's raster: cell centres of a lon/lat bbox, rows from north to south, projected.
std::vector<XY> lonlat_raster(const geo::BBox& box, const geo::LocalProjection& proj, std::size_t w, std::size_t h) {
  std::vector<XY> out;
  out.reserve(w * h);
  for (std::size_t j = 0; j < h; ++j)
    for (std::size_t i = 0; i < w; ++i)
      out.push_back(geo::project(proj, {box.min_lon + (box.max_lon - box.min_lon) * (i + 0.5) / w,
                                        box.max_lat - (box.max_lat - box.min_lat) * (j + 0.5) / h}));
  return out;
}

std::vector<metro::WorthSource> synthetic_city(std::size_t n, double side, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> centre(0, side / 10), spot(0, side / 60), station_spread(0, side / 5);
  std::uniform_real_distribution<double> flat(-side / 2, side / 2), u(0, 1);
  std::vector<XY> spots, stations;
  for (int s = 0; s < 8; ++s) spots.push_back({flat(rng) * 0.6, flat(rng) * 0.6});
  for (int s = 0; s < 150; ++s) stations.push_back({station_spread(rng), station_spread(rng)});
  std::vector<metro::WorthSource> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    XY p;
    const double pick = u(rng);
    if (pick < 0.4) {
      p = {centre(rng), centre(rng)};
    } else if (pick < 0.7) {
      const auto& s = spots[i % spots.size()];
      p = {s.x + spot(rng), s.y + spot(rng)};
    } else {
      p = {flat(rng), flat(rng)};
    }
    double d2 = 1e300;
    for (const auto& s : stations) d2 = std::min(d2, (p.x - s.x) * (p.x - s.x) + (p.y - s.y) * (p.y - s.y));
    out.push_back({p, 0.0, std::sqrt(d2) / 1000});
  }
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  for (std::size_t r = 0; r < n; ++r) out[order[r]].rank01 = static_cast<double>(r + 1) / static_cast<double>(n);
  return out;
}

model::City load_city(const store::MetroImport& m) {
  model::City city;
  city.info.id = m.city.id;
  city.metro = store::load_metro_files(m);
  city.info.bbox = model::bbox_of(city.metro);
  city.info.projection = geo::projection_for(city.info.bbox);
  return city;
}

// The endpoints' whole path for a large import: the first city's metro with n synthetic POIs
// (ranked) around its stations, as MetroService computes it (per city version: the metro data;
// per request: the worth field, the projected raster and the stations, or the POI worth).
void endpoint_section(const store::Manifest& manifest, std::size_t n) {
  if (n == 0 || manifest.metros.empty()) return;
  auto city = std::make_shared<model::City>(load_city(manifest.metros.front()));
  std::vector<geo::LonLat> stations;
  for (const auto& node : city->metro.nodes)
    if (node.is_station()) stations.push_back(node.pos);
  if (stations.empty()) return;
  std::mt19937 rng(11);
  std::normal_distribution<double> near(0, 0.004), centre(0, 0.03);
  std::uniform_int_distribution<std::size_t> pick(0, stations.size() - 1);
  const auto mid = city->info.bbox.center();
  for (std::size_t i = 0; i < n; ++i) {
    model::Poi p;
    p.id = std::to_string(i);
    p.name = "POI " + p.id;
    const bool at_station = i % 3 != 0;
    const auto base = at_station ? stations[pick(rng)] : mid;
    p.pos = {base.lon + (at_station ? near(rng) : centre(rng)) * 1.5, base.lat + (at_station ? near(rng) : centre(rng))};
    p.rank = static_cast<double>(i % 997 * 1009 % n + 1);
    city->pois.push_back(std::move(p));
  }
  std::printf("\n### The endpoints' path: %zu synthetic POIs around %s's %zu stations\n\n", n, city->info.id.c_str(),
              stations.size());
  std::printf("| step | ms | note |\n|---|---:|---|\n");
  auto t = Clock::now();
  auto data = api::make_city_metro_data(city);
  std::printf("| metro data (once per city version: projection, nearest station per POI) | %.0f | |\n", ms_since(t));
  t = Clock::now();
  auto vw = api::make_visual_worth(*data, api::RankSource::automatic, {});
  std::printf("| worth field (ranks, bandwidths) | %.1f | per request |\n", ms_since(t));
  t = Clock::now();
  auto cells = lonlat_raster(city->info.bbox, data->projection, 512, 512);
  const double project_ms = ms_since(t);
  std::printf("| raster 512x512: project the cell centres | %.1f | geo::project per cell |\n", project_ms);
  std::vector<XY> points = cells;
  for (std::size_t v = 0; v < city->metro.nodes.size(); ++v)
    if (city->metro.nodes[v].is_station()) points.push_back(data->graph.pos[v]);
  metro::WorthEvalReport report;
  t = Clock::now();
  auto worth = vw.at_points(points, {}, &report);
  std::printf("| raster 512x512 + stations: at_points | %.1f | %s, %zu exact POIs, %zu levels, %zu tiles |\n", ms_since(t),
              report.exact ? "exact" : "approx.", report.exact_sources, report.levels, report.tiles);
  t = Clock::now();
  auto poi = vw.at_points(data->poi_xy, {}, &report);
  std::printf("| POI worth (clusters' weights) | %.1f | %s, %zu exact POIs, %zu levels, %zu tiles |\n", ms_since(t),
              report.exact ? "exact" : "approx.", report.exact_sources, report.levels, report.tiles);
  std::vector<XY> layout_points = data->graph.pos;
  layout_points.insert(layout_points.end(), data->poi_xy.begin(), data->poi_xy.end());
  t = Clock::now();
  auto layout = vw.at_points(layout_points, {}, &report);
  std::printf("| layout worth (nodes + POIs) | %.1f | %s |\n", ms_since(t), report.exact ? "exact" : "approx.");
}

}  // namespace

int main(int argc, char** argv) {
  std::string data_dir = TOURMAP_DEFAULT_DATA_DIR;
  if (const char* env = std::getenv("TOURMAP_DATA_DIR")) data_dir = env;
  std::size_t max_pois = 1000000;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--data-dir") data_dir = argv[i + 1];
    if (std::string(argv[i]) == "--max-pois") max_pois = std::stoul(argv[i + 1]);
  }
  metro::WorthEvalOptions automatic, forced;
  forced.work_budget = 0;

  std::printf("# tourmap visual worth benchmark\n\n");
  std::printf("Raster: 512 x 512 cell centres (cities: the endpoint's lon/lat raster over the metro bbox, projected; "
              "synthetic: the 30 km square). POI worth: every POI. \"~\": the old loop ran on `points checked` of "
              "the points, its time scaled to all. Errors on the checked points; relative error where the exact "
              "value is >= 1e-3 of the maximum.\n\n### Sample cities\n\n");
  header();
  auto manifest = store::parse_manifest(load::read_file(TOURMAP_MANIFEST), data_dir);
  for (const auto& p : manifest.pois) {
    auto m = std::find_if(manifest.metros.begin(), manifest.metros.end(), [&](const auto& x) { return x.city.id == p.city_id; });
    if (m == manifest.metros.end()) continue;
    auto city = std::make_shared<model::City>(load_city(*m));
    city->pois = load::load_pois(p.file, {p.default_category});
    auto data = api::make_city_metro_data(city);
    auto vw = api::make_visual_worth(*data, api::RankSource::automatic, {});
    Case raster{p.city_id, vw.size(), "raster 512x512", lonlat_raster(city->info.bbox, data->projection, 512, 512)};
    Case worth{p.city_id, vw.size(), "POI worth", data->poi_xy};
    row(vw, raster, automatic);
    row(vw, worth, automatic);
    raster.data += " (forced approx.)";
    worth.data += " (forced approx.)";
    row(vw, raster, forced);
    row(vw, worth, forced);
  }

  endpoint_section(manifest, std::min<std::size_t>(max_pois, 250000));

  std::printf("\n### Synthetic cities (30 x 30 km)\n\n");
  header();
  const double side = 30000;
  for (std::size_t n : {std::size_t{10000}, std::size_t{100000}, std::size_t{250000}, std::size_t{1000000}}) {
    if (n > max_pois) break;
    auto sources = synthetic_city(n, side, 7);
    std::vector<XY> poi_xy;
    for (const auto& s : sources) poi_xy.push_back(s.pos);
    metro::VisualWorth vw(std::move(sources), {});
    const std::string name = "synthetic " + (n >= 1000000 ? std::to_string(n / 1000000) + "M" : std::to_string(n / 1000) + "K");
    metro::WorthRaster grid{{-side / 2, -side / 2}, {side / 2, side / 2}, 512, 512};
    std::vector<XY> cells;
    for (std::size_t j = 0; j < grid.height; ++j)
      for (std::size_t i = 0; i < grid.width; ++i)
        cells.push_back({-side / 2 + side * (i + 0.5) / 512, side / 2 - side * (j + 0.5) / 512});
    row(vw, {name, n, "raster 512x512", cells}, automatic);
    row(vw, {name, n, "POI worth", poi_xy}, automatic);
  }
  return 0;
}
