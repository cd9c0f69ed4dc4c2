#include "deform/foldover.hpp"
#include "deform/untangle.hpp"

#include <gtest/gtest.h>

namespace tourmap::deform {
namespace {

// A long road along y = 1 over a 4 x 2 grid of unit quads, and a short one across below its
// middle, 0.05 short of it. Pushing the grid vertex (2, 1) up bends the long road's image over
// the short one, but its chord (ends barely moved) stays at y = 1 and now cuts the short road.
struct Bent {
  PlanarNetwork net;
  Prepared p;
  std::vector<XY> points;
};

Bent bent_network() {
  Bent b;
  b.net.nodes = {{0.1, 1.0}, {3.9, 1.0}, {2.0, 0.7}, {2.0, 0.95}};
  b.net.edges = {{0, 1}, {2, 3}};
  b.net.min = {0.1, 0.7};
  b.net.max = {3.9, 1.0};
  b.net.transform.metres_per_unit = 100;  // "touching" (2 m) is then 0.02 units: the roads are apart
  b.p = prepare_grid(b.net, grid::build_uniform({{0, 0}, 1.0, 4, 2}), {}, Weights{}, Boundary::fixed);
  b.points = b.p.rest;
  for (auto& v : b.points)
    if (v.x == 2 && v.y == 1) v.y += 0.3;
  return b;
}

TEST(Untangle, EveryEdgeHasSamplesAndAClearance) {
  auto b = bent_network();
  const auto& s = b.p.edge_samples;
  ASSERT_EQ(s.start.size(), 3u);
  EXPECT_GE(s.start[1] - s.start[0], 7u);  // 3.8 long, samples at most half a quad apart
  EXPECT_GE(s.start[2] - s.start[1], 1u);  // the midpoint at least
  ASSERT_EQ(s.clearance.size(), 2u);
  EXPECT_NEAR(s.clearance[0], 0.05, 1e-6);
  EXPECT_NEAR(s.clearance[1], 0.05, 1e-6);
}

TEST(Untangle, SmoothsAwayACrossingTheChordsAdded) {
  auto b = bent_network();
  ASSERT_EQ(count_inverted_quads(*b.p.grid, b.points), 0u);
  ASSERT_EQ(count_added_crossings(b.net, road_nodes_from(b.p, b.points)), 1u);
  std::vector<XY> nodes;
  const auto report = untangle_crossings(b.p, b.net, b.points, nodes, 60);
  EXPECT_GT(report.steps, 0);
  EXPECT_GE(report.suspects, 1u);
  EXPECT_EQ(report.left, 0u);
  EXPECT_EQ(count_added_crossings(b.net, nodes), 0u);
  const auto placed = road_nodes_from(b.p, b.points);  // the nodes it returns are where the grid puts them
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    EXPECT_DOUBLE_EQ(nodes[i].x, placed[i].x);
    EXPECT_DOUBLE_EQ(nodes[i].y, placed[i].y);
  }
  EXPECT_EQ(count_inverted_quads(*b.p.grid, b.points), 0u);
}

TEST(Untangle, ReportsWhatIsLeftWhenTheStepsRunOut) {
  auto b = bent_network();
  std::vector<XY> nodes;
  const auto report = untangle_crossings(b.p, b.net, b.points, nodes, 0);
  EXPECT_EQ(report.steps, 0);
  EXPECT_EQ(report.left, 1u);
}

TEST(Untangle, RoadsLessThanALaneApartCountAsTouching) {
  auto b = bent_network();
  b.net.transform.metres_per_unit = 1;  // the 0.05 gap is now 5 cm: they touched at rest
  EXPECT_EQ(count_added_crossings(b.net, road_nodes_from(b.p, b.points)), 0u);
}

}  // namespace
}  // namespace tourmap::deform
