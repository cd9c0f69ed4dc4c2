#include "metro/grid_chains.hpp"

#include <gtest/gtest.h>

namespace tourmap::metro::octi {
namespace {

using Nodes = std::vector<std::uint32_t>;

// Stations on a line 100 m apart; edges with their lines, every target length 10.
LayoutGraph graph(std::size_t stations, std::vector<std::pair<std::uint32_t, std::uint32_t>> edges,
                  std::vector<std::vector<std::uint32_t>> lines = {}) {
  LayoutGraph g;
  for (std::size_t i = 0; i < stations; ++i) g.pos.push_back({100.0 * static_cast<double>(i), 0});
  g.edges = std::move(edges);
  g.edge_lines = lines.empty() ? std::vector<std::vector<std::uint32_t>>(g.edges.size(), {0}) : std::move(lines);
  g.min_length.assign(g.edges.size(), 10.0);
  return g;
}

TEST(GridChains, PathOfDegreeTwoStationsIsOneChain) {
  auto g = graph(5, {{0, 1}, {2, 1}, {2, 3}, {3, 4}});
  std::vector<bool> anchor;
  auto chains = contract_chains(g, anchor);
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_EQ(chains[0].nodes, (Nodes{0, 1, 2, 3, 4}));
  EXPECT_EQ(chains[0].edges, (Nodes{0, 1, 2, 3}));
  EXPECT_EQ(chains[0].forward, (std::vector<bool>{true, false, true, true}));  // edge 1 runs 2 -> 1
  EXPECT_EQ(anchor, (std::vector<bool>{true, false, false, false, true}));
}

TEST(GridChains, SplitAtStationsOfDegreeThreeOrMore) {
  // A T: 0-1-2-3 with a branch 2-4-5.
  auto g = graph(6, {{0, 1}, {1, 2}, {2, 3}, {2, 4}, {4, 5}});
  std::vector<bool> anchor;
  auto chains = contract_chains(g, anchor);
  ASSERT_EQ(chains.size(), 3u);
  EXPECT_EQ(chains[0].nodes, (Nodes{0, 1, 2}));
  EXPECT_EQ(chains[1].nodes, (Nodes{2, 3}));
  EXPECT_EQ(chains[2].nodes, (Nodes{2, 4, 5}));
  EXPECT_TRUE(anchor[2]);
  EXPECT_FALSE(anchor[1]);
  EXPECT_FALSE(anchor[4]);
}

TEST(GridChains, SplitWhereTheLineSetChanges) {
  // Lines {0, 1} on 0-1-2, only {0} on 2-3-4: station 2 ends both chains. The line order and
  // repeats within an edge do not matter.
  auto g = graph(5, {{0, 1}, {1, 2}, {2, 3}, {3, 4}}, {{1, 0}, {0, 1, 1}, {0}, {0}});
  std::vector<bool> anchor;
  auto chains = contract_chains(g, anchor);
  ASSERT_EQ(chains.size(), 2u);
  EXPECT_EQ(chains[0].nodes, (Nodes{0, 1, 2}));
  EXPECT_EQ(chains[0].lines, (Nodes{0, 1}));
  EXPECT_EQ(chains[1].nodes, (Nodes{2, 3, 4}));
  EXPECT_EQ(chains[1].lines, (Nodes{0}));
  EXPECT_FALSE(anchor[1]);
  EXPECT_TRUE(anchor[2]);
  EXPECT_FALSE(anchor[3]);
}

TEST(GridChains, GivenAnchorsStayChainEnds) {
  auto g = graph(5, {{0, 1}, {1, 2}, {2, 3}, {3, 4}});
  std::vector<bool> anchor(5, false);
  anchor[3] = true;  // e.g. an end of an edge that crosses another geographically
  auto chains = contract_chains(g, anchor);
  ASSERT_EQ(chains.size(), 2u);
  EXPECT_EQ(chains[0].nodes, (Nodes{0, 1, 2, 3}));
  EXPECT_EQ(chains[1].nodes, (Nodes{3, 4}));
}

TEST(GridChains, CycleOfDegreeTwoStationsIsSplitInTwo) {
  // A ring of four stations: one station becomes an anchor, and the chain that would return
  // to it is split at its middle station.
  auto g = graph(4, {{0, 1}, {1, 2}, {2, 3}, {3, 0}});
  std::vector<bool> anchor;
  auto chains = contract_chains(g, anchor);
  ASSERT_EQ(chains.size(), 2u);
  EXPECT_EQ(chains[0].nodes, (Nodes{0, 1, 2}));
  EXPECT_EQ(chains[1].nodes, (Nodes{2, 3, 0}));
  EXPECT_EQ(chains[1].edges, (Nodes{2, 3}));
  EXPECT_EQ(anchor, (std::vector<bool>{true, false, true, false}));
}

TEST(GridChains, EveryEdgeInExactlyOneChain) {
  // Two stations joined twice (parallel edges), a tail and a separate ring.
  auto g = graph(8, {{0, 1}, {1, 0}, {1, 2}, {2, 3}, {4, 5}, {5, 6}, {6, 7}, {7, 4}});
  std::vector<bool> anchor;
  auto chains = contract_chains(g, anchor);
  std::vector<int> seen(g.edges.size(), 0);
  for (const auto& c : chains) {
    ASSERT_EQ(c.nodes.size(), c.edges.size() + 1);
    EXPECT_TRUE(anchor[c.nodes.front()]);
    EXPECT_TRUE(anchor[c.nodes.back()]);
    for (std::size_t k = 1; k + 1 < c.nodes.size(); ++k) EXPECT_FALSE(anchor[c.nodes[k]]);
    for (auto e : c.edges) ++seen[e];
  }
  EXPECT_EQ(seen, std::vector<int>(g.edges.size(), 1));
}

TEST(GridChains, NodeSharesFollowTargetLengths) {
  auto g = graph(4, {{0, 1}, {1, 2}, {2, 3}});
  g.min_length = {10, 30, 60};
  std::vector<bool> anchor;
  auto chains = contract_chains(g, anchor);
  ASSERT_EQ(chains.size(), 1u);
  auto t = node_shares(g, chains[0]);
  ASSERT_EQ(t.size(), 4u);
  EXPECT_DOUBLE_EQ(t[0], 0.0);
  EXPECT_DOUBLE_EQ(t[1], 0.1);
  EXPECT_DOUBLE_EQ(t[2], 0.4);
  EXPECT_DOUBLE_EQ(t[3], 1.0);
  g.min_length = {0, 0, 0};  // no lengths: equal shares
  t = node_shares(g, chains[0]);
  EXPECT_DOUBLE_EQ(t[1], 1.0 / 3);
  EXPECT_DOUBLE_EQ(t[2], 2.0 / 3);
}

TEST(GridChains, StationsPutBackInOrderAtTheirShare) {
  // Chain 0-1-2-3 with target lengths 1, 3, 4 along a path of length 16 (8 east, 8 north):
  // stations at 2 and 8 units along it. Edge 2 is stored 3 -> 2: its piece runs that way.
  auto g = graph(4, {{0, 1}, {1, 2}, {3, 2}});
  g.min_length = {1, 3, 4};
  std::vector<bool> anchor;
  auto chains = contract_chains(g, anchor);
  ASSERT_EQ(chains.size(), 1u);
  ASSERT_EQ(chains[0].nodes, (Nodes{0, 1, 2, 3}));
  Layout L;
  L.pos.assign(4, {-1, -1});
  L.paths.assign(3, {});
  unroll_chain(g, chains[0], {{0, 0}, {8, 0}, {8, 8}}, L);
  EXPECT_DOUBLE_EQ(L.pos[1].x, 2.0);
  EXPECT_DOUBLE_EQ(L.pos[1].y, 0.0);
  EXPECT_DOUBLE_EQ(L.pos[2].x, 8.0);
  EXPECT_DOUBLE_EQ(L.pos[2].y, 0.0);
  EXPECT_EQ(L.pos[0].x, -1.0);  // anchors are the caller's
  ASSERT_EQ(L.paths[0].size(), 2u);
  EXPECT_DOUBLE_EQ(L.paths[0].back().x, 2.0);
  ASSERT_EQ(L.paths[1].size(), 2u);
  EXPECT_DOUBLE_EQ(L.paths[1].front().x, 2.0);
  EXPECT_DOUBLE_EQ(L.paths[1].back().x, 8.0);
  ASSERT_EQ(L.paths[2].size(), 2u);
  EXPECT_DOUBLE_EQ(L.paths[2].front().y, 8.0);  // from station 3...
  EXPECT_DOUBLE_EQ(L.paths[2].back().y, 0.0);   // ...to station 2
}

TEST(GridChains, PieceKeepsTheBendInside) {
  auto g = graph(3, {{0, 1}, {1, 2}});
  g.min_length = {1, 1};
  std::vector<bool> anchor;
  auto chains = contract_chains(g, anchor);
  Layout L;
  L.pos.assign(3, {0, 0});
  L.paths.assign(2, {});
  // Length 8; station 1 at 4 units, after the bend at (2, 0).
  unroll_chain(g, chains[0], {{0, 0}, {2, 0}, {2, 6}}, L);
  EXPECT_DOUBLE_EQ(L.pos[1].x, 2.0);
  EXPECT_DOUBLE_EQ(L.pos[1].y, 2.0);
  ASSERT_EQ(L.paths[0].size(), 3u);
  EXPECT_DOUBLE_EQ(L.paths[0][1].x, 2.0);
  EXPECT_DOUBLE_EQ(L.paths[0][1].y, 0.0);
  ASSERT_EQ(L.paths[1].size(), 2u);
}

TEST(GridChains, PolylineHelpers) {
  std::vector<XY> line = {{0, 0}, {1, 0}, {2, 0}, {2, 2}};
  auto s = simplify_collinear(line);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[1].x, 2.0);
  auto mid = point_along(line, 0.5);
  EXPECT_DOUBLE_EQ(mid.x, 2.0);
  EXPECT_DOUBLE_EQ(mid.y, 0.0);
  EXPECT_EQ(point_along(line, 0).x, 0.0);
  EXPECT_EQ(point_along(line, 1).y, 2.0);
  auto part = sub_polyline(line, 0.25, 0.75);
  ASSERT_EQ(part.size(), 3u);
  EXPECT_DOUBLE_EQ(part.front().x, 1.0);
  EXPECT_DOUBLE_EQ(part[1].x, 2.0);
  EXPECT_DOUBLE_EQ(part.back().y, 1.0);
}

TEST(GridChains, EndAngleIsTheGeographicDirectionFromTheAnchor) {
  LayoutGraph g;
  g.pos = {{0, 0}, {0, 100}, {100, 100}};
  g.edges = {{0, 1}, {1, 2}};
  g.edge_lines = {{0}, {0}};
  g.min_length = {10, 10};
  std::vector<bool> anchor;
  auto chains = contract_chains(g, anchor);
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_DOUBLE_EQ(end_angle(g, chains[0], true), M_PI / 2);  // north from station 0
  EXPECT_DOUBLE_EQ(end_angle(g, chains[0], false), M_PI);     // west from station 2
}

}  // namespace
}  // namespace tourmap::metro::octi
