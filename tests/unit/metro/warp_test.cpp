#include "metro/visual_worth.hpp"
#include "metro/warp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tourmap::metro {
namespace {

TEST(Helmert, RecoversAKnownSimilarity) {
  Helmert truth{1.7 * std::cos(0.4), 1.7 * std::sin(0.4), 120.0, -35.0};
  std::vector<XY> from, to;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> coord(-500, 500);
  for (int i = 0; i < 30; ++i) {
    XY p{coord(rng), coord(rng)};
    from.push_back(p);
    to.push_back(truth.apply(p));
  }
  auto h = fit_helmert(from, to);
  EXPECT_NEAR(h.scale(), 1.7, 1e-12);
  EXPECT_NEAR(h.rotation(), 0.4, 1e-12);
  EXPECT_NEAR(h.tx, 120.0, 1e-9);
  EXPECT_NEAR(h.ty, -35.0, 1e-9);
}

TEST(Helmert, LeastSquaresUnderNoiseAndDegenerateInput) {
  std::vector<XY> from = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  std::vector<XY> to = {{0.1, 0}, {20, -0.1}, {20.1, 20}, {0, 19.9}};  // scale 2, small noise
  auto h = fit_helmert(from, to);
  EXPECT_NEAR(h.scale(), 2.0, 0.01);
  EXPECT_NEAR(h.rotation(), 0.0, 0.01);
  auto identity = fit_helmert({{1, 1}}, {{5, 5}});
  EXPECT_EQ(identity.a, 1.0);
}

TEST(Warp, InterpolatesControlPointsAndIsSmoothBetween) {
  std::vector<XY> from = {{0, 0}, {100, 0}, {100, 100}, {0, 100}, {50, 50}};
  std::vector<XY> to = {{0, 0}, {100, 0}, {100, 100}, {0, 100}, {60, 45}};  // the centre moved
  Warp warp(from, to);
  for (std::size_t i = 0; i < from.size(); ++i) {
    auto w = warp(from[i]);
    EXPECT_NEAR(w.x, to[i].x, 1e-6);
    EXPECT_NEAR(w.y, to[i].y, 1e-6);
  }
  auto between = warp({50, 25});
  EXPECT_GT(between.x, 50.0);  // pulled along with the centre
  EXPECT_LT(between.x, 60.0);
  // Far away the displacement stays bounded (no linear blow-up).
  auto far = warp({100000, 100000});
  EXPECT_LT(std::hypot(far.x - 100000, far.y - 100000), 50.0);
  // Duplicate control points do not break the system.
  Warp dup({{0, 0}, {0, 0}, {10, 0}}, {{0, 0}, {0, 0}, {20, 0}});
  EXPECT_NEAR(dup({10, 0}).x, 20.0, 1e-6);
}

TEST(VisualWorth, PopularAndNearStationPoisWeighMore) {
  WorthParams params;
  // Two POIs 5 km apart: rank 1 next to a station, and the last rank 2 km from one.
  VisualWorth vw({{{0, 0}, 0.5, 0.0}, {{5000, 0}, 1.0, 2.0}}, params);
  EXPECT_LT(vw.bandwidth(0), vw.bandwidth(1));
  EXPECT_GT(vw.at({0, 0}), vw.at({5000, 0}));
  EXPECT_GT(vw.at({0, 0}), vw.at({300, 0}));  // peaks at the POI
  EXPECT_EQ(vw.at({100000, 0}), 0.0);         // beyond every kernel's reach
  // eq. 5.1 at a lone POI's centre: 1/n * 1/h^2 * 1/(2 pi h^2)
  VisualWorth one({{{0, 0}, 1.0, 0.0}}, params);
  double h = one.bandwidth(0);
  EXPECT_NEAR(one.at({0, 0}), 1.0 / (h * h) / (2 * M_PI * h * h), 1e-20);
  EXPECT_EQ(VisualWorth({}, params).at({0, 0}), 0.0);
}

TEST(VisualWorth, RanksFromScores) {
  EXPECT_EQ(ranks01_from_scores({3.0, 10.0, 3.0, 1.0}), (std::vector<double>{0.5, 0.25, 0.75, 1.0}));
}

}  // namespace
}  // namespace tourmap::metro
