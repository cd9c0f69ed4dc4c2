// min_station_gap (metro/station_gap.hpp, reported by measure_layout) and the comparison
// figures of metro_compare.py (metro/layout_metrics.hpp) on hand-made layouts whose answers are
// known, and the gap's grid search against brute force on larger random layouts.

#include "metro/layout_metrics.hpp"
#include "metro/layout_quality.hpp"
#include "metro/station_gap.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace tourmap::metro {
namespace {

// A layout whose edges are straight between their nodes, unless `paths` says otherwise.
struct Drawing {
  LayoutGraph g;
  Layout layout;
};

Drawing straight(const std::vector<XY>& pos, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges) {
  Drawing d;
  d.g.pos = pos;
  d.g.edges = edges;
  d.g.edge_lines.assign(edges.size(), {});
  d.g.min_length.assign(edges.size(), 10.0);
  d.layout.pos = pos;
  for (auto [u, v] : edges) d.layout.paths.push_back({pos[u], pos[v]});
  return d;
}

double point_segment(XY p, XY a, XY b) {
  double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

double brute_force_gap(const LayoutGraph& g, const Layout& L) {
  double best = std::numeric_limits<double>::infinity();
  auto joined = [&](std::uint32_t a, std::uint32_t b) {
    for (auto [u, v] : g.edges)
      if ((u == a && v == b) || (u == b && v == a)) return true;
    return false;
  };
  for (std::uint32_t v = 0; v < L.pos.size(); ++v) {
    for (std::uint32_t w = v + 1; w < L.pos.size(); ++w)
      if (!joined(v, w)) best = std::min(best, std::hypot(L.pos[v].x - L.pos[w].x, L.pos[v].y - L.pos[w].y));
    for (std::size_t e = 0; e < g.edges.size(); ++e) {
      if (g.edges[e].first == v || g.edges[e].second == v) continue;
      for (std::size_t i = 1; i < L.paths[e].size(); ++i)
        best = std::min(best, point_segment(L.pos[v], L.paths[e][i - 1], L.paths[e][i]));
    }
  }
  return best;
}

TEST(StationGap, TwoParallelEdges) {
  auto d = straight({{0, 0}, {10, 0}, {0, 3}, {10, 3}}, {{0, 1}, {2, 3}});
  EXPECT_DOUBLE_EQ(min_station_gap(d.g, d.layout), 3.0);
}

TEST(StationGap, JoinedNeighboursDoNotCountHowEverClose) {
  // 0-1 are 1 apart but joined; the nearest unjoined things are 50 apart.
  auto d = straight({{0, 0}, {1, 0}, {0, 50}, {1, 50}}, {{0, 1}, {2, 3}});
  EXPECT_DOUBLE_EQ(min_station_gap(d.g, d.layout), 50.0);
}

TEST(StationGap, NodeNextToAnotherEdgesPath) {
  // Node 2 at (5, 2) hangs over the middle of edge 0-1: 2 from its path, sqrt(29) from its ends.
  auto d = straight({{0, 0}, {10, 0}, {5, 2}, {5, 10}}, {{0, 1}, {2, 3}});
  EXPECT_DOUBLE_EQ(min_station_gap(d.g, d.layout), 2.0);
}

TEST(StationGap, BentPathsCountEverySegment) {
  // Edge 0-2 runs (0,0) -> (10,0) -> (10,10); node 3 at (7,7) is 3 from its vertical leg,
  // sqrt(18) from node 2 and farther from everything else.
  auto d = straight({{0, 0}, {5, -20}, {10, 10}, {7, 7}, {0, 10}}, {{0, 2}, {3, 4}, {0, 1}});
  d.layout.paths[0] = {{0, 0}, {10, 0}, {10, 10}};
  EXPECT_DOUBLE_EQ(min_station_gap(d.g, d.layout), 3.0);
  EXPECT_DOUBLE_EQ(brute_force_gap(d.g, d.layout), 3.0);
}

TEST(StationGap, FarApartPiecesGrowTheGrid) {
  // The gap (999) is far larger than the mean segment (1): the grid's cells must grow.
  auto d = straight({{0, 0}, {1, 0}, {1000, 0}, {1001, 0}}, {{0, 1}, {2, 3}});
  EXPECT_DOUBLE_EQ(min_station_gap(d.g, d.layout), 999.0);
}

TEST(StationGap, NoPairAtAllIsInfinite) {
  auto d = straight({{0, 0}, {10, 0}}, {{0, 1}});
  EXPECT_TRUE(std::isinf(min_station_gap(d.g, d.layout)));
}

TEST(StationGap, MatchesBruteForceOnRandomLayouts) {
  std::mt19937 rng(7);
  for (int round = 0; round < 20; ++round) {
    std::uniform_real_distribution<double> coord(0, round % 2 ? 100.0 : 5000.0);
    std::vector<XY> pos;
    const std::size_t n = 40 + 15 * static_cast<std::size_t>(round);
    for (std::size_t i = 0; i < n; ++i) pos.push_back({coord(rng), coord(rng)});
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (std::uint32_t i = 1; i < n; ++i) edges.push_back({i - 1, i});
    auto d = straight(pos, edges);
    // Octilinear-looking paths: a diagonal then a straight leg, as the grid router draws them.
    for (std::size_t e = 0; e < edges.size(); ++e) {
      XY a = pos[edges[e].first], b = pos[edges[e].second];
      double dx = b.x - a.x, dy = b.y - a.y, m = std::min(std::abs(dx), std::abs(dy));
      XY bend{a.x + std::copysign(m, dx), a.y + std::copysign(m, dy)};
      d.layout.paths[e] = {a, bend, b};
    }
    EXPECT_DOUBLE_EQ(min_station_gap(d.g, d.layout), brute_force_gap(d.g, d.layout)) << "round " << round;
  }
}

TEST(LayoutQuality, ReportsTheGapAndItsRatioToTheMeanEdge) {
  auto d = straight({{0, 0}, {10, 0}, {0, 3}, {10, 3}}, {{0, 1}, {2, 3}});
  auto q = measure_layout(d.g, d.layout);
  EXPECT_DOUBLE_EQ(q.mean_edge, 10.0);
  EXPECT_DOUBLE_EQ(q.min_station_gap, 3.0);
  EXPECT_DOUBLE_EQ(q.min_station_gap_ratio, 0.3);
}

TEST(CompareMetrics, BendsAlongDegreeTwoChains) {
  // Stations 0, 1, 2 on a line that turns 90 degrees at station 1 (a station bend); junction 3
  // of degree 2 between 2 and 4 is contracted, and the path of 2-3 turns once inside (an
  // interior bend); at station 2 the line goes straight on (north in, north out).
  auto d = straight({{0, 0}, {10, 0}, {10, 10}, {20, 20}, {30, 20}}, {{0, 1}, {1, 2}, {2, 3}, {3, 4}});
  d.layout.paths[2] = {{10, 10}, {10, 20}, {20, 20}};
  std::vector<bool> station = {true, true, true, false, true};
  auto m = metro_compare_metrics(d.g, station, d.layout);
  EXPECT_EQ(m.edges, 3u);  // 2-3 and 3-4 became one
  EXPECT_EQ(m.edges_kept, 3u);
  EXPECT_EQ(m.interior_bends, 1u);
  EXPECT_EQ(m.station_bends, 1u);
  EXPECT_EQ(m.bends, 2u);
  EXPECT_EQ(m.pieces, 4u);  // 0-1, 1-2, and 2-4 as north + east (the junction's east-east merged)
  EXPECT_DOUBLE_EQ(m.octilinear_share, 1.0);
}

TEST(CompareMetrics, ReversalsCountAndDegreeThreeStationsDoNot) {
  // Station 1 has degree 3: no station bend, whatever its lines do. At station 3 (degree 2)
  // the line arrives heading east and leaves heading west (a reversal: one bend); the path of
  // 3-4 then turns inside (another).
  auto d = straight({{0, 0}, {10, 0}, {10, 10}, {20, 0}, {10, -10}}, {{0, 1}, {1, 2}, {1, 3}, {3, 4}});
  d.layout.paths[3] = {{20, 0}, {12, 0}, {10, -10}};
  std::vector<bool> station(5, true);
  auto m = metro_compare_metrics(d.g, station, d.layout);
  EXPECT_EQ(m.station_bends, 1u);
  EXPECT_EQ(m.interior_bends, 1u);
  EXPECT_LT(m.octilinear_share, 1.0);  // (12,0) -> (10,-10) is not at a multiple of 45 degrees
}

TEST(CompareMetrics, DisplacementIsTheRmsOfASimilarityFitOverTheDiagonal) {
  auto d = straight({{0, 0}, {300, 0}, {300, 400}, {0, 400}}, {{0, 1}, {1, 2}, {2, 3}});
  std::vector<bool> station(4, true);
  // A rotated, scaled, shifted copy: no displacement.
  for (auto& p : d.layout.pos) p = {0.5 * p.y + 7, -0.5 * p.x + 3};
  for (std::size_t e = 0; e < d.g.edges.size(); ++e)
    d.layout.paths[e] = {d.layout.pos[d.g.edges[e].first], d.layout.pos[d.g.edges[e].second]};
  EXPECT_NEAR(metro_compare_metrics(d.g, station, d.layout).displacement, 0.0, 1e-12);
  // The rectangle made 20 wider in the layout: by symmetry the fit is a pure scale
  // a = sum(z . w) / sum(|z|^2) about the common centre, and every corner is left off by the
  // same residual (160 a - 150, 200 - 200 a); the diagonal of the geography is 500.
  d.layout.pos = {{-10, 0}, {310, 0}, {310, 400}, {-10, 400}};
  for (std::size_t e = 0; e < d.g.edges.size(); ++e)
    d.layout.paths[e] = {d.layout.pos[d.g.edges[e].first], d.layout.pos[d.g.edges[e].second]};
  const double a = 4 * (160.0 * 150 + 200.0 * 200) / (4 * (160.0 * 160 + 200.0 * 200));
  EXPECT_NEAR(metro_compare_metrics(d.g, station, d.layout).displacement, std::hypot(160 * a - 150, 200 - 200 * a) / 500,
              1e-12);
}

TEST(CompareMetrics, MinOverMeanEdgeAfterContraction) {
  // Edges 10, 10 and (through junction 3) 5 + 15 = 20: min 10 / mean 40/3.
  auto d = straight({{0, 0}, {10, 0}, {20, 0}, {25, 0}, {40, 0}}, {{0, 1}, {1, 2}, {2, 3}, {3, 4}});
  std::vector<bool> station = {true, true, true, false, true};
  auto m = metro_compare_metrics(d.g, station, d.layout);
  EXPECT_EQ(m.edges, 3u);
  EXPECT_DOUBLE_EQ(m.min_over_mean_edge, 10.0 / (40.0 / 3.0));
  EXPECT_EQ(m.bends, 0u);
}

}  // namespace
}  // namespace tourmap::metro
