// Batched visual worth (core/metro/visual_worth.hpp): exact within the work budget, the
// approximation within its documented bound above it, and cooperative stopping.
#include "metro/visual_worth.hpp"
#include "util/stop.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <random>

namespace tourmap::metro {
namespace {

// A city-like set: a dense centre, a few hot spots and a sparse spread over `side` metres;
// ranks 1..n in random order, stations every ~2 km (rho from a jittered lattice).
std::vector<WorthSource> synthetic(std::size_t n, double side, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> centre(0, side / 10), spot(0, side / 60);
  std::uniform_real_distribution<double> flat(-side / 2, side / 2), u(0, 1);
  std::vector<XY> spots;
  for (int s = 0; s < 6; ++s) spots.push_back({flat(rng) * 0.6, flat(rng) * 0.6});
  std::vector<WorthSource> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    XY p;
    const double pick = u(rng);
    if (pick < 0.4) p = {centre(rng), centre(rng)};
    else if (pick < 0.7) {
      const auto& s = spots[i % spots.size()];
      p = {s.x + spot(rng), s.y + spot(rng)};
    } else p = {flat(rng), flat(rng)};
    const double sx = std::fmod(std::fabs(p.x), 2000.0), sy = std::fmod(std::fabs(p.y), 2000.0);
    const double station_km = std::hypot(std::min(sx, 2000 - sx), std::min(sy, 2000 - sy)) / 1000 * (0.5 + u(rng));
    out.push_back({p, 0.0, station_km});
  }
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  for (std::size_t r = 0; r < n; ++r) out[order[r]].rank01 = static_cast<double>(r + 1) / n;
  return out;
}

TEST(VisualWorthBatch, EqualsScalarExactlyOnSmallInputs) {
  auto sources = synthetic(400, 12000, 1);
  VisualWorth vw(sources, {});
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> coord(-9000, 9000);
  std::vector<XY> points;
  for (int i = 0; i < 3000; ++i) points.push_back({coord(rng), coord(rng)});
  for (const auto& s : sources) points.push_back(s.pos);
  points.push_back({1e7, -1e7});  // beyond every kernel
  WorthEvalReport report;
  auto batched = vw.at_points(points, {}, &report);
  EXPECT_TRUE(report.exact);
  EXPECT_GT(report.estimated_work, 0.0);
  ASSERT_EQ(batched.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) ASSERT_EQ(batched[i], vw.at(points[i])) << i;

  WorthRaster grid{{-8000, -5000}, {8000, 6000}, 40, 25};
  auto raster = vw.raster(grid, {}, &report);
  EXPECT_TRUE(report.exact);
  ASSERT_EQ(raster.size(), 40u * 25u);
  for (std::size_t j = 0; j < 25; ++j)
    for (std::size_t i = 0; i < 40; ++i) {
      XY c{-8000 + 400.0 * (i + 0.5), 6000 - 440.0 * (j + 0.5)};  // rows from north to south
      ASSERT_EQ(raster[j * 40 + i], vw.at(c)) << i << "," << j;
    }

  EXPECT_TRUE(VisualWorth({}, {}).at_points(points).size() == points.size());
  EXPECT_EQ(VisualWorth({}, {}).at_points(points)[0], 0.0);
  EXPECT_TRUE(vw.at_points({}).empty());
}

// Every kernel alone (POIs far apart, bandwidths over many levels), all on the grids: the
// documented per-kernel bound as a function of d / h.
TEST(VisualWorthBatch, ApproximatedKernelsWithinTheirBound) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  WorthParams params;
  std::vector<WorthSource> sources;
  const int n = 60;
  for (int i = 0; i < n; ++i)  // h from 60 m to ~2400 m, 40 km apart
    sources.push_back({{40000.0 * i + 123.4 * u(rng), 3000.0 * u(rng)}, u(rng), 3.0 * u(rng)});
  VisualWorth vw(sources, params);
  std::vector<XY> points;
  std::vector<std::pair<int, double>> of;  // POI, d / h
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 300; ++k) {
      const double r = 4.2 * std::sqrt(u(rng)), a = 2 * M_PI * u(rng), h = vw.bandwidth(i);
      points.push_back({sources[i].pos.x + r * h * std::cos(a), sources[i].pos.y + r * h * std::sin(a)});
      of.push_back({i, r});
    }
  WorthEvalOptions options;
  options.work_budget = 0;
  options.grids_only = true;
  WorthEvalReport report;
  auto approx = vw.at_points(points, options, &report);
  EXPECT_FALSE(report.exact);
  EXPECT_EQ(report.exact_sources, 0u);
  EXPECT_GT(report.levels, 20u);
  double worst2 = 0, worst3 = 0, worst_peak = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double h = vw.bandwidth(of[k].first), peak = 1 / (2 * M_PI * h * h * h * h) / n;
    const double exact = vw.at(points[k]), err = std::fabs(approx[k] - exact);
    if (of[k].second <= 2) worst2 = std::max(worst2, err / exact);
    else if (of[k].second <= 3) worst3 = std::max(worst3, err / exact);
    worst_peak = std::max(worst_peak, err / peak);
  }
  EXPECT_LE(worst2, kWorthKernelErrorWithin2h) << worst2;
  EXPECT_LE(worst3, kWorthKernelErrorWithin3h) << worst3;
  EXPECT_LE(worst_peak, kWorthKernelErrorOfPeak) << worst_peak;
}

// A large synthetic city: the automatic choice approximates, within the field's bound.
TEST(VisualWorthBatch, LargeSetWithinTheBound) {
  auto sources = synthetic(40000, 25000, 4);
  VisualWorth vw(sources, {});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coord(-12000, 12000);
  std::vector<XY> points;
  for (int i = 0; i < 60000; ++i) points.push_back({coord(rng), coord(rng)});
  for (std::size_t i = 0; i < sources.size(); i += 4) points.push_back(sources[i].pos);
  WorthEvalReport report;
  auto approx = vw.at_points(points, {}, &report);
  EXPECT_FALSE(report.exact);
  EXPECT_GT(report.estimated_work, 1e8);
  EXPECT_LT(report.exact_sources, sources.size() / 4);  // most POIs on the grids
  EXPECT_GT(report.tiles, 0u);
  // Against the exact sums on a sample (the full exact run is the cost the approximation avoids).
  double max_exact = 0;
  std::vector<std::pair<std::size_t, double>> sample;
  for (std::size_t k = 0; k < points.size(); k += 97) {
    sample.push_back({k, vw.at(points[k])});
    max_exact = std::max(max_exact, sample.back().second);
  }
  double worst_rel = 0, worst_abs = 0, mean_rel = 0;
  std::size_t counted = 0;
  for (const auto& [k, exact] : sample) {
    const double err = std::fabs(approx[k] - exact);
    worst_abs = std::max(worst_abs, err / max_exact);
    if (exact >= 1e-3 * max_exact) {
      worst_rel = std::max(worst_rel, err / exact);
      mean_rel += err / exact;
      ++counted;
    }
  }
  mean_rel /= std::max<std::size_t>(counted, 1);
  EXPECT_GT(counted, sample.size() / 2);
  EXPECT_LE(worst_rel, kWorthKernelErrorWithin2h) << worst_rel;
  EXPECT_LE(mean_rel, 0.005) << mean_rel;
  EXPECT_LE(worst_abs, kWorthKernelErrorOfPeak) << worst_abs;
}

TEST(VisualWorthBatch, StopsWithAnExpiredToken) {
  auto sources = synthetic(3000, 10000, 6);
  VisualWorth vw(sources, {});
  util::StopToken token;
  token.deadline = util::StopToken::Clock::now() - std::chrono::seconds(1);
  WorthRaster grid{{-5000, -5000}, {5000, 5000}, 256, 256};
  {
    util::StopScope scope(token);
    EXPECT_THROW(vw.raster(grid), util::Stopped);  // the exact path
    WorthEvalOptions approximate;
    approximate.work_budget = 0;
    EXPECT_THROW(vw.raster(grid, approximate), util::Stopped);
  }
  // A deadline passing mid-way: the exact loop (a budget that keeps a long job exact) stops.
  {
    util::StopToken soon;
    soon.deadline = util::StopToken::Clock::now() + std::chrono::milliseconds(20);
    util::StopScope scope(soon);
    WorthEvalOptions exact;
    exact.work_budget = 1e15;
    WorthRaster big{{-5000, -5000}, {5000, 5000}, 1024, 1024};  // ~10^9 kernels: minutes
    const auto started = util::StopToken::Clock::now();
    EXPECT_THROW(vw.raster(big, exact), util::Stopped);
    EXPECT_LT(std::chrono::duration<double>(util::StopToken::Clock::now() - started).count(), 30.0);
  }
  std::atomic<bool> gone{true};
  util::StopToken client;
  client.cancelled = &gone;
  util::StopScope scope(client);
  try {
    vw.at_points(std::vector<XY>(10, XY{0, 0}));
    FAIL() << "expected util::Stopped";
  } catch (const util::Stopped& e) {
    EXPECT_EQ(e.reason, util::Stopped::Reason::client_gone);
  }
}

}  // namespace
}  // namespace tourmap::metro
