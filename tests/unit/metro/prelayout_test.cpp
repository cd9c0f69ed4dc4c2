#include "metro/prelayout.hpp"

#include "shared_networks.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tourmap::metro {
namespace {

using test_networks::graph;

// A path with geographic edges of 1, 1 and 10 (mean 4) and minimum lengths of 10 (mean 10):
// the scale is 2.5 per metre, 1.75 at 0.7 of it. The short edges keep their minimum, the long
// one gets 0.7 of its scaled geographic length.
TEST(StressLengths, LongEdgesKeepMostOfTheirGeographicLength) {
  auto g = graph({{0, 0}, {1, 0}, {2, 0}, {12, 0}}, {{0, 1}, {1, 2}, {2, 3}});
  const auto lengths = stress_lengths(g, 0.7);
  ASSERT_EQ(lengths.size(), 3u);
  EXPECT_DOUBLE_EQ(lengths[0], 10);
  EXPECT_DOUBLE_EQ(lengths[1], 10);
  EXPECT_DOUBLE_EQ(lengths[2], 17.5);
  // Never below an edge's minimum, whatever the share.
  for (double share : {0.0, 0.3, 1.0, 2.0})
    for (std::size_t i = 0; i < g.edges.size(); ++i) EXPECT_GE(stress_lengths(g, share)[i], g.min_length[i]);
}

// The stress layout from those targets keeps the long edge longer than the short ones: the
// periphery is not pulled in to the minimum length.
TEST(StressLengths, TheStressLayoutFollowsThem) {
  auto g = graph({{0, 0}, {1, 0}, {2, 0}, {12, 0}}, {{0, 1}, {1, 2}, {2, 3}});
  auto stretched = g;
  stretched.min_length = stress_lengths(g);
  const auto x = stress_layout(stretched, scale_to_lengths(stretched));
  const double short_edge = std::hypot(x[1].x - x[0].x, x[1].y - x[0].y);
  const double long_edge = std::hypot(x[3].x - x[2].x, x[3].y - x[2].y);
  EXPECT_NEAR(short_edge, 10, 1.0);
  EXPECT_NEAR(long_edge, 17.5, 1.75);
}

}  // namespace
}  // namespace tourmap::metro
