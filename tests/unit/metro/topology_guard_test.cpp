#include "metro/prelayout.hpp"
#include "metro/topology_guard.hpp"

#include "metro/layout_quality.hpp"
#include "shared_networks.hpp"

#include <gtest/gtest.h>

namespace tourmap::metro {
namespace {

using test_networks::graph;

TEST(TopologyGuard, SegmentsIntersect) {
  EXPECT_TRUE(segments_intersect({0, 0}, {2, 2}, {0, 2}, {2, 0}));
  EXPECT_FALSE(segments_intersect({0, 0}, {1, 0}, {0, 1}, {1, 1}));
  EXPECT_TRUE(segments_intersect({0, 0}, {2, 0}, {1, 0}, {1, 5}));  // touching counts
  EXPECT_FALSE(segments_intersect({0, 0}, {1, 0}, {2, 0}, {3, 0}));  // collinear apart
}

TEST(TopologyGuard, RejectsMovesThatChangeCrossings) {
  // A horizontal line 0-1, and node 2 above it hanging from node 3 further up.
  auto g = graph({{0, 0}, {10, 0}, {5, 2}, {5, 8}}, {{0, 1}, {2, 3}});
  auto guard = make_topology_guard(g, g.pos);
  EXPECT_TRUE(move_keeps_topology(guard, g, g.pos, 2, {6, 3}));
  EXPECT_FALSE(move_keeps_topology(guard, g, g.pos, 2, {5, -2}));  // its edge would cross 0-1
  // Starting crossed, the crossing must stay.
  auto crossed = graph({{0, 0}, {10, 0}, {5, -2}, {5, 8}}, {{0, 1}, {2, 3}});
  auto crossed_guard = make_topology_guard(crossed, crossed.pos);
  EXPECT_FALSE(move_keeps_topology(crossed_guard, crossed, crossed.pos, 2, {5, 2}));
  EXPECT_TRUE(move_keeps_topology(crossed_guard, crossed, crossed.pos, 2, {4, -3}));
}

TEST(TopologyGuard, RejectsSweepingOverANodeAndChangingTheCircularOrder) {
  // Node 4 ends an edge to the east, just below edge 0-1: swinging node 1 from above it to
  // below it sweeps edge 0-1 over node 4 without any crossing before or after.
  auto g = graph({{0, 0}, {10, 5}, {30, 0}, {40, 0}, {8, 0}}, {{0, 1}, {2, 3}, {4, 3}});
  auto guard = make_topology_guard(g, g.pos);
  EXPECT_FALSE(move_keeps_topology(guard, g, g.pos, 1, {10, -5}));
  EXPECT_TRUE(move_keeps_topology(guard, g, g.pos, 1, {8, 6}));
  // A star: centre 0 with neighbours east, north, west; moving the north one past the west
  // one (far round, no crossing) swaps the circular order at the centre.
  auto star = graph({{0, 0}, {10, 0}, {0, 10}, {-10, 0}}, {{0, 1}, {0, 2}, {0, 3}});
  auto star_guard = make_topology_guard(star, star.pos);
  EXPECT_TRUE(move_keeps_topology(star_guard, star, star.pos, 2, {-3, 9}));
  EXPECT_FALSE(move_keeps_topology(star_guard, star, star.pos, 2, {-10, -1}));
}

TEST(StressLayout, KeepsLondonsCrossingsWhenAsked) {
  auto g = test_networks::london();
  auto straight = [&](const std::vector<XY>& pos) {
    std::vector<std::vector<XY>> lines;
    for (auto [a, b] : g.edges) lines.push_back({pos[a], pos[b]});
    return crossing_path_pairs(lines, g.edges);
  };
  const auto geo = straight(g.pos);
  ASSERT_GT(geo.size(), 5u);  // London's lines cross without shared stations
  auto init = scale_to_lengths(g);
  EXPECT_EQ(straight(init), geo);
  auto kept = stress_layout(g, init);
  EXPECT_EQ(straight(kept), geo);
  // Unguarded, the stress layout changes them (why the guard exists).
  StressOptions free;
  free.keep_topology = false;
  EXPECT_NE(straight(stress_layout(g, init, free)), geo);
  // And it still spreads the network: mean edge length moves towards the target of 10.
  auto mean_length = [&](const std::vector<XY>& pos) {
    double sum = 0;
    for (auto [a, b] : g.edges) sum += std::hypot(pos[a].x - pos[b].x, pos[a].y - pos[b].y);
    return sum / static_cast<double>(g.edges.size());
  };
  auto spread = [&](const std::vector<XY>& pos) {  // relative spread of edge lengths
    double mean = mean_length(pos), var = 0;
    for (auto [a, b] : g.edges) {
      double l = std::hypot(pos[a].x - pos[b].x, pos[a].y - pos[b].y);
      var += (l - mean) * (l - mean);
    }
    return std::sqrt(var / static_cast<double>(g.edges.size())) / mean;
  };
  EXPECT_LT(spread(kept), spread(init));
}

}  // namespace
}  // namespace tourmap::metro
