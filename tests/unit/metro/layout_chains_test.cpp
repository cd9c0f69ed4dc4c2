#include "metro/layout_chains.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace tourmap::metro {
namespace {

LayoutGraph graph(std::size_t nodes, std::vector<std::pair<std::uint32_t, std::uint32_t>> edges) {
  LayoutGraph g;
  g.pos.assign(nodes, {0, 0});
  g.edges = std::move(edges);
  g.edge_lines.assign(g.edges.size(), {0});
  g.min_length.assign(g.edges.size(), 10);
  return g;
}

TEST(LayoutChains, ChainsRunBetweenNodesOfDegreeOtherThanTwo) {
  // Hub 0 with three arms: 0-1-2 (terminus 2), 0-3 (terminus 3), 0-4-5-6 (terminus 6); edges in
  // mixed directions.
  auto g = graph(7, {{1, 0}, {1, 2}, {0, 3}, {4, 0}, {5, 4}, {5, 6}});
  auto chains = layout_chains(g);
  ASSERT_EQ(chains.size(), 3u);
  std::size_t edges = 0;
  for (const auto& c : chains) {
    EXPECT_EQ(c.inner.size() + 1, c.edges.size());
    EXPECT_TRUE(c.a == 0 || c.b == 0);
    edges += c.edges.size();
    // Walk the chain: each edge joins the previous node to the next.
    std::uint32_t at = c.a;
    for (std::size_t i = 0; i < c.edges.size(); ++i) {
      auto [u, v] = g.edges[c.edges[i]];
      EXPECT_EQ(c.forward[i] ? u : v, at);
      at = c.forward[i] ? v : u;
      if (i + 1 < c.edges.size()) {
        EXPECT_EQ(at, c.inner[i]);
      }
    }
    EXPECT_EQ(at, c.b);
  }
  EXPECT_EQ(edges, g.edges.size());
  auto longest = std::max_element(chains.begin(), chains.end(), [](auto& x, auto& y) { return x.edges.size() < y.edges.size(); });
  EXPECT_EQ(longest->inner, (std::vector<std::uint32_t>{4, 5}));
}

TEST(LayoutChains, APureCycleIsOneChainFromOneOfItsNodesBackToIt) {
  auto g = graph(4, {{0, 1}, {1, 2}, {2, 3}, {3, 0}});
  auto chains = layout_chains(g);
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_EQ(chains[0].a, chains[0].b);
  EXPECT_EQ(chains[0].edges.size(), 4u);
  EXPECT_EQ(chains[0].inner.size(), 3u);
}

TEST(LayoutChains, ChainPolylineJoinsTheEdgePathsInChainOrder) {
  auto g = graph(3, {{1, 0}, {1, 2}});
  Layout layout;
  layout.pos = {{0, 0}, {1, 0}, {2, 1}};
  layout.paths = {{{1, 0}, {0, 0}}, {{1, 0}, {2, 0}, {2, 1}}};
  auto chains = layout_chains(g);
  ASSERT_EQ(chains.size(), 1u);
  auto pts = chain_polyline(chains[0], layout);
  ASSERT_EQ(pts.size(), 4u);
  const XY a = layout.pos[chains[0].a];
  EXPECT_DOUBLE_EQ(pts.front().x, a.x);
  EXPECT_DOUBLE_EQ(pts.front().y, a.y);
}

}  // namespace
}  // namespace tourmap::metro
