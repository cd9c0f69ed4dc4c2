#include "metro/octilinear_shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tourmap::metro {
namespace {

bool octilinear(const std::vector<XY>& pts) {
  for (std::size_t i = 1; i < pts.size(); ++i)
    if (octant_of({pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y}, 1e-9) < 0) return false;
  return true;
}

TEST(OctilinearShapes, OctantOfNamesTheEightDirections) {
  EXPECT_EQ(octant_of({5, 0}, 1e-9), 0);
  EXPECT_EQ(octant_of({2, 2}, 1e-9), 1);
  EXPECT_EQ(octant_of({0, 3}, 1e-9), 2);
  EXPECT_EQ(octant_of({-1, 1}, 1e-9), 3);
  EXPECT_EQ(octant_of({-4, 0}, 1e-9), 4);
  EXPECT_EQ(octant_of({-1, -1}, 1e-9), 5);
  EXPECT_EQ(octant_of({0, -7}, 1e-9), 6);
  EXPECT_EQ(octant_of({3, -3}, 1e-9), 7);
  EXPECT_EQ(octant_of({3, 1}, 1e-9), -1);
  EXPECT_EQ(octant_of({0, 0}, 1e-9), -1);
}

TEST(OctilinearShapes, AlignedPointsGetTheStraightLineAlone) {
  auto shapes = octilinear_shapes({1, 1}, {4, 4}, 1e-9);
  ASSERT_EQ(shapes.size(), 1u);
  EXPECT_EQ(shapes[0].bends, 0);
  EXPECT_EQ(shapes[0].corners.size(), 2u);
}

TEST(OctilinearShapes, OtherPointsGetOneBendShapesInBothOrdersAndTwoZs) {
  const XY p{0, 0}, q{3, 1};
  auto shapes = octilinear_shapes(p, q, 1e-9);
  // 6 pairs of directions (one 45, two 90, three 135 degrees apart) in two orders, 2 Zs.
  ASSERT_EQ(shapes.size(), 14u);
  int one_bend = 0, by_turn[4] = {0, 0, 0, 0};
  for (const auto& s : shapes) {
    EXPECT_TRUE(octilinear(s.corners));
    EXPECT_NEAR(s.corners.front().x, p.x, 1e-12);
    EXPECT_NEAR(s.corners.back().x, q.x, 1e-12);
    EXPECT_NEAR(s.corners.back().y, q.y, 1e-12);
    EXPECT_EQ(static_cast<int>(s.corners.size()), s.bends + 2);
    EXPECT_EQ(polyline_bends(s.corners), s.bends);
    if (s.bends == 1) ++one_bend, ++by_turn[s.turn45];
  }
  EXPECT_EQ(one_bend, 12);
  EXPECT_EQ(by_turn[1], 2);  // diagonal then east, east then diagonal
  EXPECT_EQ(by_turn[2], 4);
  EXPECT_EQ(by_turn[3], 6);
}

TEST(OctilinearShapes, PolylineArithmetic) {
  const std::vector<XY> l = {{0, 0}, {4, 0}, {4, 3}};
  EXPECT_DOUBLE_EQ(polyline_length(l), 7.0);
  EXPECT_EQ(polyline_bends(l), 1);
  const XY m = point_at_length(l, 5.0);
  EXPECT_DOUBLE_EQ(m.x, 4.0);
  EXPECT_DOUBLE_EQ(m.y, 1.0);
  const auto pts = points_at_lengths(l, {0.0, 1.0, 4.0, 6.5, 7.0});
  ASSERT_EQ(pts.size(), 3u);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const XY want = point_at_length(l, std::vector<double>{1.0, 4.0, 6.5}[i]);
    EXPECT_DOUBLE_EQ(pts[i].x, want.x);
    EXPECT_DOUBLE_EQ(pts[i].y, want.y);
  }
  const auto mid = polyline_between(l, 2.0, 5.0);
  ASSERT_EQ(mid.size(), 3u);  // (2,0), the corner, (4,1)
  EXPECT_DOUBLE_EQ(mid[1].x, 4.0);
  EXPECT_DOUBLE_EQ(mid[1].y, 0.0);
  EXPECT_DOUBLE_EQ(polyline_length(mid), 3.0);
}

TEST(OctilinearShapes, SimplifyDropsRepeatsAndStraightRunsButKeepsReversals) {
  const auto s = simplify_polyline({{0, 0}, {1, 0}, {1, 0}, {2, 0}, {3, 1}}, 1e-9);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_DOUBLE_EQ(s[1].x, 2.0);
  const auto back = simplify_polyline({{0, 0}, {2, 0}, {1, 0}}, 1e-9);  // a reversal is a vertex
  EXPECT_EQ(back.size(), 3u);
}

}  // namespace
}  // namespace tourmap::metro
