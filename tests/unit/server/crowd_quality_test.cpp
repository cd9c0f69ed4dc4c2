#include "server/crowd_quality.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tourmap::server {
namespace {

TEST(CrowdFrameQuality, LevelZeroIsTheRequestItself) {
  const FrameQuality f = frame_quality(0, 1280, 720, 0.5f, 75);
  EXPECT_EQ(f.width, 1280);
  EXPECT_EQ(f.height, 720);
  EXPECT_FLOAT_EQ(f.cut_poe, 0.5f);
  EXPECT_EQ(f.jpeg_quality, 75);
}

TEST(CrowdFrameQuality, CoarserLevelsShrinkTheFrameAndCoarsenTheCutInClientPixels) {
  int previous_width = 1281;
  float previous_client_poe = 0;
  for (int level = 0; level < QualityController::kLevels; ++level) {
    const FrameQuality f = frame_quality(level, 1280, 720, 0.5f, 90);
    EXPECT_LT(f.width, previous_width) << level;
    EXPECT_NEAR(static_cast<double>(f.width) / f.height, 1280.0 / 720.0, 0.01) << level;
    // The cut's PoE at the rendered size, back in the client's pixels, grows level by level.
    const float client_poe = f.cut_poe * 720.f / static_cast<float>(f.height);
    EXPECT_GE(client_poe, previous_client_poe) << level;
    EXPECT_LE(f.jpeg_quality, 90);
    previous_width = f.width;
    previous_client_poe = client_poe;
  }
  EXPECT_EQ(frame_quality(99, 64, 64, 1, 50).level, QualityController::kLevels - 1);  // clamped
  EXPECT_GE(frame_quality(5, 20, 20, 1, 50).height, 16);
}

TEST(CrowdQualityController, CoarsensUntilTheCostFitsTheBudget) {
  QualityController c;
  // Full quality costs 140 ms; the budget is 60 ms (15 fps): down at once by the assumed ratio.
  c.record(0, 140);
  EXPECT_EQ(c.choose(frame_budget_ms(15, 1)), 3);  // 140 / 1.4^2 = 71 > 60; 140 / 1.4^3 = 51 <= 60
  EXPECT_NEAR(c.predicted_ms(3), 140 / (1.4 * 1.4 * 1.4), 1e-9);
}

TEST(CrowdQualityController, InterpolatesBetweenMeasuredLevels) {
  QualityController c;
  c.record(0, 110);
  c.record(5, 42);  // vertex-bound: the smallest frame still costs 42 ms
  const double ratio = std::pow(110.0 / 42.0, 1.0 / 5);
  EXPECT_NEAR(c.predicted_ms(4), 42 * ratio, 1e-9);
  EXPECT_NEAR(c.predicted_ms(1), 110 / ratio, 1e-9);
  c.level = 5;
  EXPECT_EQ(c.choose(60), 4);  // 42 x 1.21 = 51 <= 0.9 x 60: one finer
  c.record(4, 58);
  EXPECT_EQ(c.choose(60), 4);  // level 3: 58 x (110 / 58)^(1/4) = 68 > 54
}

TEST(CrowdQualityController, GoesFinerOneLevelAtATimeWhileThereIsRoom) {
  QualityController c;
  c.level = 4;
  c.record(4, 5);  // far below the budget
  EXPECT_EQ(c.choose(50), 3);
  c.record(3, 9);
  EXPECT_EQ(c.choose(50), 2);
  c.record(2, 34);
  EXPECT_EQ(c.choose(50), 2);  // level 1 predicted 34 x 1.4 = 48 ms: over 0.9 x 50
  c.record(2, 34);
  EXPECT_EQ(c.choose(50), 2);  // stays: no flip-flopping
}

TEST(CrowdQualityController, MeasuredCostsWinOverTheAssumedRatio) {
  QualityController c;
  c.record(0, 40);
  c.record(1, 39);  // the scene is not limited by what the levels change
  c.level = 1;
  EXPECT_EQ(c.choose(60), 0);
  c.record(0, 120);  // the view got heavy: smoothed 0.6 * 40 + 0.4 * 120 = 72
  EXPECT_NEAR(c.predicted_ms(0), 72, 1e-9);
  EXPECT_EQ(c.choose(60), 1);
}

TEST(CrowdQualityController, SharesTheBudgetBetweenStreamsAndIgnoresBadSamples) {
  EXPECT_NEAR(frame_budget_ms(15, 1), 0.9 * 1000 / 15, 1e-9);
  EXPECT_NEAR(frame_budget_ms(15, 4), 0.9 * 1000 / 15 / 4, 1e-9);
  EXPECT_EQ(frame_budget_ms(0, 1), 0);
  QualityController c;
  c.record(0, -1);
  c.record(0, std::numeric_limits<double>::quiet_NaN());
  c.record(7, 10);
  EXPECT_EQ(c.predicted_ms(0), 0);
  EXPECT_EQ(c.choose(10), 0);  // nothing measured: the finest first
}

}  // namespace
}  // namespace tourmap::server
