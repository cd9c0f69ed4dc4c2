// Interest weights in visual worth (core/metro/visual_worth.hpp, WorthSource::weight): weight 1
// is the paper's eq. 5.1 to the bit; other weights scale each POI's kernel, on the exact sums
// and on the approximation (within its documented bound); n stays the count of all POIs.
#include "metro/visual_worth.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace tourmap::metro {
namespace {

std::vector<WorthSource> scattered(std::size_t n, double side, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coord(-side / 2, side / 2), u(0, 1);
  std::vector<WorthSource> out;
  for (std::size_t i = 0; i < n; ++i) out.push_back({{coord(rng), coord(rng)}, u(rng), 3 * u(rng)});
  return out;
}

std::vector<XY> probe_points(std::size_t n, double side, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coord(-side / 2, side / 2);
  std::vector<XY> out;
  for (std::size_t i = 0; i < n; ++i) out.push_back({coord(rng), coord(rng)});
  return out;
}

TEST(VisualWorthInterests, WeightOneIsThePapersFieldBitForBit) {
  auto sources = scattered(500, 10000, 1);
  auto ones = sources;
  for (auto& s : ones) s.weight = 1.0;
  VisualWorth a(sources, {}), b(ones, {});
  const auto points = probe_points(2000, 10000, 2);
  for (const auto& p : points) ASSERT_EQ(a.at(p), b.at(p));
  WorthEvalOptions approx;
  approx.work_budget = 0;
  approx.grids_only = true;
  EXPECT_EQ(a.at_points(points), b.at_points(points));
  EXPECT_EQ(a.at_points(points, approx), b.at_points(points, approx));
}

// The field is linear in the weights: (1/n) sum_i w_i k_i(u), k_i the POI's kernel alone.
TEST(VisualWorthInterests, EachKernelScaledByItsWeight) {
  auto sources = scattered(200, 6000, 3);
  const double weights[] = {0.0, 0.5, 1.0, 2.0, 10.0};
  for (std::size_t i = 0; i < sources.size(); ++i) sources[i].weight = weights[i % 5];
  VisualWorth weighted(sources, {});
  std::vector<VisualWorth> alone;
  for (auto s : sources) {
    s.weight = 1.0;
    alone.emplace_back(std::vector<WorthSource>{s}, WorthParams{});
  }
  const auto points = probe_points(300, 6000, 4);
  const auto batched = weighted.at_points(points);
  double max = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    double expected = 0;
    for (std::size_t i = 0; i < sources.size(); ++i) expected += sources[i].weight * alone[i].at(points[k]);
    expected /= static_cast<double>(sources.size());
    max = std::max(max, expected);
    EXPECT_NEAR(weighted.at(points[k]), expected, 1e-12 * expected + 1e-300) << k;
    EXPECT_EQ(batched[k], weighted.at(points[k])) << k;
  }
  EXPECT_GT(max, 0.0);
}

TEST(VisualWorthInterests, WeightZeroRemovesThePoi) {
  std::vector<WorthSource> sources = {{{0, 0}, 0.1, 0.2}, {{50000, 0}, 0.1, 0.2}};
  sources[1].weight = 0;
  VisualWorth vw(sources, {});
  EXPECT_EQ(vw.at({50000, 0}), 0.0);
  EXPECT_GT(vw.at({0, 0}), 0.0);
  // n stays 2: the other POI's value is half its value alone.
  VisualWorth alone({sources[0]}, {});
  EXPECT_DOUBLE_EQ(vw.at({0, 0}), alone.at({0, 0}) / 2);
}

// The approximation carries the weights: against the exact weighted sums, within the
// documented per-kernel bound with each kernel scaled by its weight (weights >= 0), summed
// over the kernels at each point.
TEST(VisualWorthInterests, ApproximationFollowsTheWeights) {
  auto sources = scattered(3000, 20000, 5);
  for (std::size_t i = 0; i < sources.size(); ++i) sources[i].weight = i % 3 == 0 ? 0.0 : i % 3 == 1 ? 0.25 : 4.0;
  VisualWorth vw(sources, {});
  const auto points = probe_points(1500, 20000, 6);
  WorthEvalOptions options;
  options.work_budget = 0;
  options.grids_only = true;
  WorthEvalReport report;
  const auto approx = vw.at_points(points, options, &report);
  EXPECT_FALSE(report.exact);
  const double n = static_cast<double>(sources.size());
  std::size_t nonzero = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    double bound = 0;
    for (std::size_t i = 0; i < sources.size(); ++i) {
      const double h = vw.bandwidth(i), d = std::hypot(points[k].x - sources[i].pos.x, points[k].y - sources[i].pos.y);
      const double peak = sources[i].weight / (2 * M_PI * h * h * h * h) / n;
      const double value = peak * std::exp(-d * d / (2 * h * h));
      if (d <= 2 * h) bound += kWorthKernelErrorWithin2h * value;
      else if (d <= 3 * h) bound += kWorthKernelErrorWithin3h * value;
      else if (d <= 6 * h) bound += kWorthKernelErrorOfPeak * peak;
    }
    const double exact = vw.at(points[k]);
    if (exact > 0) ++nonzero;
    EXPECT_LE(std::fabs(approx[k] - exact), bound + 1e-300) << k << " exact " << exact;
  }
  EXPECT_GT(nonzero, points.size() / 2);
}

}  // namespace
}  // namespace tourmap::metro
