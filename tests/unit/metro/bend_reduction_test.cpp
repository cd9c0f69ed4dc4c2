#include "metro/bend_reduction.hpp"

#include "metro/layout_chains.hpp"
#include "metro/layout_quality.hpp"
#include "metro/octilinear_grid.hpp"
#include "metro/octilinear_shapes.hpp"
#include "metro/prelayout.hpp"
#include "metro/segment_geometry.hpp"
#include "shared_networks.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tourmap::metro {
namespace {

using test_networks::graph;

// Bends along chains, as a reader (and ../shared/tools/metro_compare.py) counts them.
std::size_t chain_bends(const LayoutGraph& g, const Layout& layout) {
  std::size_t bends = 0;
  for (const auto& c : layout_chains(g)) bends += polyline_bends(simplify_polyline(chain_polyline(c, layout), 1e-9));
  return bends;
}

// Smallest distance between stations not joined by an edge, and from a station to an edge it is
// not on, over the mean edge length (an independent check of the clearance rule).
double min_gap_over_mean_edge(const LayoutGraph& g, const Layout& layout) {
  const std::size_t n = layout.pos.size();
  std::vector<std::vector<std::uint32_t>> joined(n);
  double mean = 0;
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    joined[g.edges[e].first].push_back(g.edges[e].second);
    joined[g.edges[e].second].push_back(g.edges[e].first);
    mean += polyline_length(layout.paths[e]) / g.edges.size();
  }
  double gap = 1e300;
  for (std::uint32_t v = 0; v < n; ++v) {
    for (std::uint32_t w = v + 1; w < n; ++w)
      if (std::find(joined[v].begin(), joined[v].end(), w) == joined[v].end())
        gap = std::min(gap, std::hypot(layout.pos[v].x - layout.pos[w].x, layout.pos[v].y - layout.pos[w].y));
    for (std::size_t e = 0; e < g.edges.size(); ++e) {
      if (g.edges[e].first == v || g.edges[e].second == v) continue;
      const auto& p = layout.paths[e];
      for (std::size_t i = 1; i < p.size(); ++i) gap = std::min(gap, point_segment_distance(layout.pos[v], p[i - 1], p[i]));
    }
  }
  return gap / mean;
}

TEST(BendReduction, AStaircaseBetweenTwoTerminiBecomesStraight) {
  // Two termini on one horizontal line, three stations between them drawn as a staircase.
  auto g = graph({{0, 0}, {1000, 0}, {2000, 0}, {3000, 0}, {4000, 0}}, {{0, 1}, {1, 2}, {2, 3}, {3, 4}});
  Layout layout;
  layout.pos = {{0, 0}, {10, 2}, {20, 0}, {30, 2}, {40, 0}};
  layout.paths = {{{0, 0}, {8, 0}, {10, 2}},
                  {{10, 2}, {18, 2}, {20, 0}},
                  {{20, 0}, {28, 0}, {30, 2}},
                  {{30, 2}, {38, 2}, {40, 0}}};
  ASSERT_GT(chain_bends(g, layout), 4u);
  BendReductionReport report;
  reduce_bends(g, layout, {}, &report);
  EXPECT_EQ(report.chains, 1u);
  EXPECT_EQ(report.bends_after, 0u);
  EXPECT_EQ(chain_bends(g, layout), 0u);
  for (std::size_t v = 1; v < 5; ++v) EXPECT_GT(layout.pos[v].x, layout.pos[v - 1].x) << "stations keep their order";
  for (const auto& p : layout.paths) {
    EXPECT_EQ(p.size(), 2u);
    EXPECT_NEAR(p.front().y, p.back().y, 1e-9);
  }
}

TEST(BendReduction, AShortTerminusEdgeGetsItsShareOfTheLine) {
  // A straight line whose last edge the router squeezed to a tenth of the others.
  auto g = graph({{0, 0}, {1000, 0}, {2000, 0}, {3000, 0}}, {{0, 1}, {1, 2}, {2, 3}});
  Layout layout;
  layout.pos = {{0, 0}, {10, 0}, {20, 0}, {21, 0}};
  layout.paths = {{{0, 0}, {10, 0}}, {{10, 0}, {20, 0}}, {{20, 0}, {21, 0}}};
  ASSERT_LT(min_gap_over_mean_edge(g, layout), 0.2);
  reduce_bends(g, layout);
  EXPECT_EQ(chain_bends(g, layout), 0u);
  EXPECT_GE(min_gap_over_mean_edge(g, layout), 0.5);
  for (std::size_t v = 1; v < 4; ++v) EXPECT_GT(layout.pos[v].x, layout.pos[v - 1].x) << "stations keep their order";
}

TEST(BendReduction, ALoopDrawnTinyOpensUp) {
  // A line ending in a loop (as at Heathrow): 0 - 1, then 1 - 2 - 3 - 1. The router drew the
  // loop a tenth of the line's edge; the loop is one chain from 1 back to 1.
  auto g = graph({{0, 0}, {1000, 0}, {2000, 500}, {2000, -500}}, {{0, 1}, {1, 2}, {2, 3}, {3, 1}});
  Layout layout;
  layout.pos = {{0, 0}, {10, 0}, {11, 1}, {11, -1}};
  layout.paths = {{{0, 0}, {10, 0}}, {{10, 0}, {11, 1}}, {{11, 1}, {11, -1}}, {{11, -1}, {10, 0}}};
  ASSERT_LT(min_gap_over_mean_edge(g, layout), 0.3);
  const auto before = measure_layout(g, layout);
  reduce_bends(g, layout);
  const auto after = measure_layout(g, layout);
  EXPECT_GE(min_gap_over_mean_edge(g, layout), 0.5);
  EXPECT_EQ(after.octilinear_share, 1.0);
  EXPECT_LE(after.added_crossings, before.added_crossings);
  EXPECT_LE(after.order_violations, before.order_violations);
}

TEST(BendReduction, KeepsAGeographicCrossingAndAddsNone) {
  // Two lines that cross without a shared station, each drawn with jogs.
  auto g = graph({{-2000, 0}, {0, -300}, {2000, 0}, {0, -2000}, {300, 0}, {0, 2000}}, {{0, 1}, {1, 2}, {3, 4}, {4, 5}});
  auto start = stress_layout(g, scale_to_lengths(g));
  auto layout = route_octilinear(g, start, {});
  const auto before = measure_layout(g, layout);
  ASSERT_EQ(before.crossings, 1u);
  reduce_bends(g, layout);
  const auto after = measure_layout(g, layout);
  EXPECT_EQ(after.crossings, 1u);
  EXPECT_EQ(after.added_crossings, 0u);
  EXPECT_EQ(after.octilinear_share, 1.0);
}

TEST(BendReduction, ViennaLosesMostBendsAndStaysAValidDrawing) {
  auto g = test_networks::vienna();
  auto start = stress_layout(g, scale_to_lengths(g));
  auto layout = route_octilinear(g, start, {});
  const auto before = measure_layout(g, layout);
  const std::size_t bends_before = chain_bends(g, layout);
  const double gap_before = min_gap_over_mean_edge(g, layout);
  BendReductionParams params;
  params.time_limit_ms = 5000;  // the result, not the budget, is under test
  BendReductionReport report;
  reduce_bends(g, layout, params, &report);
  const auto after = measure_layout(g, layout);
  EXPECT_EQ(report.bends_before, bends_before);
  EXPECT_EQ(report.bends_after, chain_bends(g, layout));
  EXPECT_LE(report.bends_after * 3, bends_before) << "at least two thirds of the bends go";
  EXPECT_EQ(after.octilinear_share, 1.0);
  EXPECT_LE(after.added_crossings, before.added_crossings);
  EXPECT_LE(after.order_violations, before.order_violations);
  EXPECT_LT(gap_before, 0.5) << "the routed drawing is cramped somewhere...";
  EXPECT_GE(min_gap_over_mean_edge(g, layout), 0.5) << "...and gets room: half a mean edge everywhere";
  EXPECT_GE(after.min_edge, 0.5 * 10 - 1e-9) << "no edge below half its target";
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    const auto& p = layout.paths[e];
    const XY a = layout.pos[g.edges[e].first], b = layout.pos[g.edges[e].second];
    EXPECT_NEAR(p.front().x, a.x, 1e-9);
    EXPECT_NEAR(p.front().y, a.y, 1e-9);
    EXPECT_NEAR(p.back().x, b.x, 1e-9);
    EXPECT_NEAR(p.back().y, b.y, 1e-9);
  }
}

TEST(BendReduction, FlawedInputStaysValid) {
  // Two stations at one point (moved apart by the graph builder's rule) and an edge straight
  // across the city between two termini of other lines.
  std::vector<XY> pos = {{0, 0}, {1000, 0}, {2000, 0}, {2000, 0}, {2000, 1000}, {0, 2000}, {1000, 2000}};
  auto g = graph(pos, {{0, 1}, {1, 2}, {3, 4}, {2, 3}, {5, 6}, {0, 6}});
  separate_coincident(g, 15);
  auto start = stress_layout(g, scale_to_lengths(g));
  auto layout = route_octilinear(g, start, {});
  const auto before = measure_layout(g, layout);
  reduce_bends(g, layout);
  const auto after = measure_layout(g, layout);
  EXPECT_EQ(after.octilinear_share, before.octilinear_share);
  EXPECT_LE(after.added_crossings, before.added_crossings);
  EXPECT_LE(after.order_violations, before.order_violations);
  EXPECT_LE(chain_bends(g, layout), chain_bends(g, route_octilinear(g, start, {})));
}

TEST(BendReduction, EmptyAndMismatchedInputsAreLeftAlone) {
  LayoutGraph g;
  Layout layout;
  BendReductionReport report;
  reduce_bends(g, layout, {}, &report);
  EXPECT_EQ(report.chains, 0u);
  auto g2 = graph({{0, 0}, {1, 0}}, {{0, 1}});
  reduce_bends(g2, layout, {}, &report);  // no paths: nothing to do
  EXPECT_TRUE(layout.paths.empty());
}

}  // namespace
}  // namespace tourmap::metro
