#include "deform/applications.hpp"
#include "deform/foldover.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace tourmap::deform {
namespace {

PlanarNetwork two_edges() {
  PlanarNetwork net;
  net.nodes = {{0, 0}, {2, 0}, {10, 0}, {12, 0}};
  net.edges = {{0, 1}, {2, 3}};
  return net;
}

TEST(Focus, EdgeMidpointsDecideAndOverlapsTakeTheLargestScale) {
  auto net = two_edges();
  FocusRegion circle{{}, {1, 0}, 0.5, 3.0};
  EXPECT_EQ(focus_edge_scales(net, {circle}), (std::vector<double>{3.0, 1.0}));
  FocusRegion square{{{9, -1}, {13, -1}, {13, 1}, {9, 1}}, {}, 0, 2.0};
  EXPECT_EQ(focus_edge_scales(net, {circle, square}), (std::vector<double>{3.0, 2.0}));
  FocusRegion bigger{{}, {1, 0}, 1.0, 5.0};
  EXPECT_EQ(focus_edge_scales(net, {circle, bigger}), (std::vector<double>{5.0, 1.0}));
}

TEST(Simplify, DouglasPeucker) {
  std::vector<XY> line = {{0, 0}, {1, 0.1}, {2, -0.1}, {3, 5}, {4, 6}, {5, 7}};
  auto s = simplify_polyline(line, 0.5);
  ASSERT_EQ(s.size(), 4u);  // the wiggle goes, the corner at (3, 5) and the ends stay
  EXPECT_EQ(s[1].x, 2);
  EXPECT_EQ(s[2].x, 3);
  EXPECT_EQ(simplify_polyline(line, 0).size(), line.size());
}

TEST(Destination, RouteVerticesGoToTheSameArcLengthFraction) {
  PlanarNetwork net;
  net.nodes = {{0, 0}, {1, 0}, {3, 0}, {4, 0}};
  auto guides = route_to_sketch(net, {0, 1, 2, 3}, {{0, 0}, {0, 8}});
  ASSERT_EQ(guides.size(), 4u);
  EXPECT_NEAR(guides[1].target.y, 2.0, 1e-12);  // 1/4 of the way
  EXPECT_NEAR(guides[2].target.y, 6.0, 1e-12);  // 3/4
  EXPECT_NEAR(guides[3].target.y, 8.0, 1e-12);
}

TEST(Guides, SortedUniqueAndNearestNode) {
  auto last_wins = sorted_guides({{3, {1, 1}}, {1, {}}, {3, {2, 2}}});
  ASSERT_EQ(last_wins.size(), 2u);
  EXPECT_EQ(last_wins[1].target.x, 2);
  EXPECT_EQ(guide_nodes(sorted_guides({{3, {}}, {1, {}}})), (std::vector<std::uint32_t>{1, 3}));
  NodeIndex index({{0, 0}, {5, 5}, {10, 0}});
  EXPECT_EQ(index.nearest({6, 4}), 1u);
  EXPECT_EQ(index.nearest({9, -3}), 2u);
}

TEST(Foldover, InvertedQuadsAndCrossings) {
  auto g = grid::build_uniform({{0, 0}, 1.0, 2, 1});
  auto pos = g.vertices;
  EXPECT_EQ(count_inverted_quads(g, pos), 0u);
  // Push the shared middle-top vertex far right: the left quad becomes non-convex/flipped.
  for (auto& p : pos)
    if (p.x == 1 && p.y == 1) p.x = 3.5;
  EXPECT_GE(count_inverted_quads(g, pos), 1u);

  std::vector<XY> nodes = {{0, 0}, {2, 2}, {0, 2}, {2, 0}, {3, 3}};
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges = {{0, 1}, {2, 3}, {1, 4}};
  EXPECT_EQ(count_crossings(nodes, edges), 1u);  // the X; 0-1 and 1-4 only share node 1
}

TEST(Foldover, SnappedTJunctionsLeaveNoCrackAtAnyLevel) {
  // Two special points refine the centre three levels deep: T-junctions at every level.
  auto g = grid::build_adaptive({{0, 0}, 1.0, 4, 4}, {}, {{2.01, 2.01}, {1.99, 1.99}}, {4, 3, 1000});
  std::set<int> levels;
  for (const auto& t : g.tjunctions) {
    levels.insert(g.quads[t.coarse_quad].level);
    // No corner of a side holding a T-junction is a T-junction itself (why order does not matter).
    for (const auto& u : g.tjunctions) {
      EXPECT_NE(g.quads[t.coarse_quad].corners[t.side], u.vertex);
      EXPECT_NE(g.quads[t.coarse_quad].corners[(t.side + 1) % 4], u.vertex);
    }
  }
  EXPECT_EQ(levels.size(), 3u);
  // A smooth but non-affine deformation, with every vertex jittered off it.
  auto pos = g.vertices;
  for (std::size_t i = 0; i < pos.size(); ++i) {
    const auto [x, y] = pos[i];
    pos[i] = {x + 0.1 * std::sin(y) + 0.01 * static_cast<double>(i % 7), y + 0.05 * x * x - 0.01 * static_cast<double>(i % 5)};
  }
  snap_tjunctions(g, pos);
  for (const auto& t : g.tjunctions) {
    const auto& c = g.quads[t.coarse_quad].corners;
    const auto a = pos[c[t.side]], b = pos[c[(t.side + 1) % 4]];
    EXPECT_NEAR(pos[t.vertex].x, (a.x + b.x) / 2, 1e-12);
    EXPECT_NEAR(pos[t.vertex].y, (a.y + b.y) / 2, 1e-12);
  }
}

TEST(Foldover, RelaxationUnfolds) {
  PlanarNetwork net;
  net.nodes = {{0.5, 0.5}, {2.5, 0.5}};
  net.edges = {{0, 1}};
  auto g = grid::build_uniform({{0, 0}, 1.0, 3, 3});
  auto p = prepare_grid(net, g, {}, Weights{}, Boundary::fixed);
  auto pos = p.rest;
  // Fold an interior vertex across its neighbour.
  for (std::size_t i = 0; i < pos.size(); ++i)
    if (pos[i].x == 1 && pos[i].y == 1) pos[i] = {2.4, 2.3};
  ASSERT_GT(count_inverted_quads(*p.grid, pos), 0u);
  int iterations = relax_foldovers(p, pos, 200);
  EXPECT_GT(iterations, 0);
  EXPECT_EQ(count_inverted_quads(*p.grid, pos), 0u);
}

}  // namespace
}  // namespace tourmap::deform
