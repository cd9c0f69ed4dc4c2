#include "metro/line_order.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace tourmap::metro {
namespace {

MipSolveFn cbc() {
  return [](const MipModel& m, double t, double gap) { return solve_with_cbc(m, t, gap); };
}

// A drawing with straight edges between the nodes' positions.
struct Net {
  LayoutGraph g;
  Layout L;
  void node(XY p) {
    g.pos.push_back(p);
    L.pos.push_back(p);
  }
  void edge(std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t> lines) {
    g.edges.push_back({a, b});
    g.edge_lines.push_back(std::move(lines));
    L.paths.push_back({L.pos[a], L.pos[b]});
    g.min_length.push_back(1);
  }
};

// Two lines share a horizontal trunk 0-1-2 and part at both ends: line 0 leaves upwards at
// both ends, line 1 downwards. On the trunk (drawn left to right, travelling east) line 0 must
// be on the left (north): no crossing at all.
Net trunk_parting_same_side() {
  Net n;
  for (XY p : {XY{0, 0}, XY{10, 0}, XY{20, 0}, XY{-10, 10}, XY{-10, -10}, XY{30, 10}, XY{30, -10}}) n.node(p);
  n.edge(0, 1, {1, 0});
  n.edge(1, 2, {0, 1});
  n.edge(3, 0, {0});
  n.edge(4, 0, {1});
  n.edge(2, 5, {0});
  n.edge(2, 6, {1});
  return n;
}

TEST(LineOrder, PairPartingOnOneSideNeverCrosses) {
  auto n = trunk_parting_same_side();
  auto r = order_lines(n.g, n.L, cbc());
  EXPECT_EQ(r.report.crossings, 0u);
  // Travelling east along the trunk, north is on the left: line 0 first.
  EXPECT_EQ(r.order[0], (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(r.order[1], (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(count_line_crossings(n.g, n.L, r.order).crossings, 0u);
  // The other order crosses at both ends of the trunk.
  EXPECT_EQ(count_line_crossings(n.g, n.L, {{1, 0}, {1, 0}, {0}, {1}, {0}, {1}}).crossings, 2u);
  // Swapping on the middle station costs one crossing there.
  EXPECT_EQ(count_line_crossings(n.g, n.L, {{0, 1}, {1, 0}, {0}, {1}, {0}, {1}}).crossings, 2u);
}

TEST(LineOrder, EdgeDrawnBackwardsMirrorsTheOrder) {
  auto n = trunk_parting_same_side();
  // The second trunk edge stored from 2 to 1: travelling west on it, north is on the right.
  n.g.edges[1] = {2, 1};
  std::reverse(n.L.paths[1].begin(), n.L.paths[1].end());
  auto r = order_lines(n.g, n.L, cbc());
  EXPECT_EQ(r.report.crossings, 0u);
  EXPECT_EQ(r.order[0], (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(r.order[1], (std::vector<std::uint32_t>{1, 0}));
}

TEST(LineOrder, SwappedEndsCrossOnceAndTheModelFindsIt) {
  // Line 0 leaves up at the west end and down at the east end, line 1 the other way: they
  // must cross once somewhere on the trunk, not more.
  auto n = trunk_parting_same_side();
  n.g.edge_lines[4] = {1};
  n.g.edge_lines[5] = {0};
  auto r = order_lines(n.g, n.L, cbc());
  EXPECT_EQ(r.report.crossings, 1u);
  EXPECT_EQ(r.report.method, "exact");
  EXPECT_DOUBLE_EQ(r.report.lower_bound, 1.0);
}

// Three lines on a trunk 0-1-2-3 where each leaves to its own side at the east end and comes
// in from a fan at the west end in the same order: the heuristic and the model agree on 0.
TEST(LineOrder, FanInFanOutKeepsTheOrder) {
  Net n;
  for (XY p : {XY{0, 0}, XY{10, 0}, XY{20, 0}, XY{30, 0}}) n.node(p);
  n.edge(0, 1, {2, 0, 1});
  n.edge(1, 2, {1, 2, 0});
  n.edge(2, 3, {0, 1, 2});
  // West fan: line 0 up-left, line 1 left, line 2 down-left; east fan mirrored.
  const XY west[] = {{-10, 10}, {-10, 0}, {-10, -10}}, east[] = {{40, 10}, {40, 0}, {40, -10}};
  for (std::uint32_t l = 0; l < 3; ++l) {
    n.node(west[l]);
    n.edge(static_cast<std::uint32_t>(n.g.pos.size() - 1), 0, {l});
    n.node(east[l]);
    n.edge(3, static_cast<std::uint32_t>(n.g.pos.size() - 1), {l});
  }
  auto r = order_lines(n.g, n.L, cbc());
  EXPECT_EQ(r.report.crossings, 0u);
  EXPECT_EQ(r.report.heuristic_crossings, 0u);
  for (std::uint32_t e = 0; e < 3; ++e) EXPECT_EQ(r.order[e], (std::vector<std::uint32_t>{0, 1, 2})) << e;
}

TEST(LineOrder, SeparationsAreCounted) {
  // Lines 0 and 2 next to each other on the first edge, line 1 between them on the second.
  Net n;
  for (XY p : {XY{0, 0}, XY{10, 0}, XY{20, 0}}) n.node(p);
  n.edge(0, 1, {0, 1, 2});
  n.edge(1, 2, {0, 1, 2});
  auto c = count_line_crossings(n.g, n.L, {{0, 2, 1}, {0, 1, 2}});
  EXPECT_EQ(c.crossings, 1u);    // 1 and 2 swap at node 1
  EXPECT_EQ(c.separations, 2u);  // (0, 2) neighbours on the first edge only, (0, 1) on the second only
  auto r = order_lines(n.g, n.L, cbc());
  EXPECT_EQ(r.report.crossings, 0u);
  EXPECT_EQ(r.report.separations, 0u);
}

TEST(LineOrder, SingleLinesNeedNoOrder) {
  Net n;
  for (XY p : {XY{0, 0}, XY{10, 0}, XY{20, 10}}) n.node(p);
  n.edge(0, 1, {0});
  n.edge(1, 2, {1});
  auto r = order_lines(n.g, n.L, cbc());
  EXPECT_EQ(r.report.method, "none");
  EXPECT_EQ(r.order[0], (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(r.report.crossings, 0u);
}

TEST(LineOrder, WithoutASolverTheHeuristicStands) {
  auto n = trunk_parting_same_side();
  n.g.edge_lines[4] = {1};
  n.g.edge_lines[5] = {0};
  auto r = order_lines(n.g, n.L, MipSolveFn{});
  EXPECT_EQ(r.report.method, "heuristic");
  EXPECT_GE(r.report.crossings, 1u);
  EXPECT_EQ(r.report.crossings, count_line_crossings(n.g, n.L, r.order).crossings);
}

}  // namespace
}  // namespace tourmap::metro
