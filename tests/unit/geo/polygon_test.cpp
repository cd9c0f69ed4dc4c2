#include "geo/polygon.hpp"

#include <gtest/gtest.h>

namespace tourmap::geo {
namespace {

Polygon square(double x0, double y0, double size) {
  return {{{x0, y0}, {x0 + size, y0}, {x0 + size, y0 + size}, {x0, y0 + size}}, {}};
}

TEST(PolygonSet, ContainsRespectsHoles) {
  Polygon outer = square(0, 0, 10);
  outer.holes.push_back(square(4, 4, 2).outer);
  PolygonSet set({outer});
  EXPECT_TRUE(set.contains({1, 1}));
  EXPECT_FALSE(set.contains({5, 5}));    // in the hole
  EXPECT_TRUE(set.contains({4, 5}));     // on the hole's boundary counts as inside the polygon
  EXPECT_TRUE(set.contains({0, 5}));     // on the outer boundary
  EXPECT_FALSE(set.contains({11, 5}));
}

TEST(PolygonSet, MultiPolygonIsUnion) {
  PolygonSet set({square(0, 0, 1), square(5, 5, 1)});
  EXPECT_TRUE(set.contains({0.5, 0.5}));
  EXPECT_TRUE(set.contains({5.5, 5.5}));
  EXPECT_FALSE(set.contains({3, 3}));
  EXPECT_DOUBLE_EQ(set.bbox().max_lon, 6.0);
}

TEST(SimpleRing, DetectsBowTieAndZeroArea) {
  EXPECT_TRUE(is_simple_ring(square(0, 0, 1).outer));
  EXPECT_FALSE(is_simple_ring({{0, 0}, {1, 1}, {1, 0}, {0, 1}}));  // bow tie
  EXPECT_FALSE(is_simple_ring({{0, 0}, {1, 1}, {2, 2}}));          // collinear: zero area
  EXPECT_FALSE(is_simple_ring({{0, 0}, {1, 1}}));
}

}  // namespace
}  // namespace tourmap::geo
