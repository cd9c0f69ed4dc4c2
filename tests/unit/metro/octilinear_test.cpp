#include "metro/octilinear_grid.hpp"

#include "metro/layout_quality.hpp"
#include "metro/prelayout.hpp"
#include "shared_networks.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tourmap::metro {
namespace {

using test_networks::graph;

Layout lay_out(const LayoutGraph& g, GridRouteReport* report = nullptr) {
  auto start = stress_layout(g, scale_to_lengths(g));
  return route_octilinear(g, start, {}, report);
}

TEST(Octilinear, FourStationSquareComesOutOctilinear) {
  // A slightly skewed quadrilateral loop in metres.
  auto g = graph({{0, 0}, {1000, 120}, {1100, 1050}, {-80, 900}}, {{0, 1}, {1, 2}, {2, 3}, {3, 0}});
  auto L = lay_out(g);
  EXPECT_EQ(L.status, "ok");
  auto q = measure_layout(g, L);
  EXPECT_EQ(q.octilinear_share, 1.0);
  EXPECT_EQ(q.crossings, 0u);
  EXPECT_EQ(q.order_violations, 0u);
  EXPECT_GT(q.min_edge, 0.0);
}

TEST(Octilinear, StarKeepsItsCircularOrderOnPlannedPorts) {
  // A hub with five spokes at irregular angles.
  std::vector<XY> pos = {{0, 0}};
  for (double a : {0.1, 1.2, 2.0, 3.5, 5.0}) pos.push_back({1000 * std::cos(a), 1000 * std::sin(a)});
  auto g = graph(pos, {{0, 1}, {0, 2}, {0, 3}, {0, 4}, {0, 5}});
  auto L = lay_out(g);
  auto q = measure_layout(g, L);
  EXPECT_EQ(q.octilinear_share, 1.0);
  EXPECT_EQ(q.order_violations, 0u);
  EXPECT_EQ(q.crossings, 0u);
}

TEST(Octilinear, ChainsAreContractedAndStationsStayInOrder) {
  // Seven stations along a gentle curve, one line: one chain after contraction.
  std::vector<XY> pos;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (int i = 0; i < 7; ++i) pos.push_back({i * 800.0, 300.0 * std::sin(i * 0.6)});
  for (std::uint32_t i = 1; i < 7; ++i) edges.push_back({i - 1, i});
  auto g = graph(pos, edges);
  GridRouteReport report;
  auto L = lay_out(g, &report);
  EXPECT_EQ(report.chains, 1u);
  EXPECT_EQ(report.contracted_nodes, 5u);
  auto q = measure_layout(g, L);
  EXPECT_EQ(q.octilinear_share, 1.0);
  // Interior stations lie on the path, in sequence: distances from the first station grow.
  for (std::uint32_t i = 1; i < 7; ++i) {
    ASSERT_EQ(L.paths[i - 1].front().x, L.pos[i - 1].x);
    ASSERT_EQ(L.paths[i - 1].back().x, L.pos[i].x);
  }
}

TEST(Octilinear, ViennaIsFullyOctilinearWithoutCrossings) {
  auto g = test_networks::vienna();
  auto L = lay_out(g);
  EXPECT_EQ(L.status, "ok");
  auto q = measure_layout(g, L);
  EXPECT_EQ(q.octilinear_share, 1.0);
  EXPECT_LE(q.crossings, q.geo_crossings);
  EXPECT_EQ(q.order_violations, 0u);
}

TEST(Octilinear, LinesThatCrossWithoutAStationCrossOnceEach) {
  // Three east-west and three north-south lines, each with four stations, crossing at nine
  // points where no station is: no planar layout exists, and each pair must cross exactly once.
  LayoutGraph g;
  const double coords[4] = {-500, 500, 1500, 2500};
  for (int line = 0; line < 6; ++line) {
    const auto first = static_cast<std::uint32_t>(g.pos.size());
    for (int k = 0; k < 4; ++k)
      g.pos.push_back(line < 3 ? XY{coords[k], 1000.0 * line} : XY{1000.0 * (line - 3), coords[k]});
    for (std::uint32_t k = 0; k + 1 < 4; ++k) {
      g.edges.push_back({first + k, first + k + 1});
      g.edge_lines.push_back({static_cast<std::uint32_t>(line)});
      g.min_length.push_back(10);
    }
  }
  GridRouteReport report;
  auto L = lay_out(g, &report);
  EXPECT_EQ(L.status, "ok");
  EXPECT_EQ(report.overlapping, 0u);
  EXPECT_EQ(report.crossing_routes, 0u);
  auto q = measure_layout(g, L);
  EXPECT_EQ(q.octilinear_share, 1.0);
  EXPECT_EQ(q.geo_crossings, 9u);
  EXPECT_EQ(q.crossings, 9u);
  EXPECT_EQ(q.added_crossings, 0u);
  EXPECT_EQ(report.crossings, 9u);
  EXPECT_EQ(report.geo_crossings, 9u);
}

TEST(Octilinear, LondonKeepsItsCrossingsAndOrders) {
  auto g = test_networks::london();
  GridRouteReport report;
  auto L = lay_out(g, &report);
  EXPECT_EQ(L.status, "ok");
  EXPECT_EQ(report.overlapping, 0u);
  auto q = measure_layout(g, L);
  EXPECT_EQ(q.octilinear_share, 1.0);
  EXPECT_GT(q.geo_crossings, 5u);
  EXPECT_EQ(q.added_crossings, 0u);
  EXPECT_EQ(q.order_violations, 0u);
  EXPECT_GT(q.min_edge, 0.0);
}

TEST(Octilinear, DisconnectedComponentsAndCoincidentStations) {
  auto g = graph({{0, 0}, {1000, 0}, {5000, 5000}, {5000, 5000}, {6000, 5200}}, {{0, 1}, {2, 4}, {3, 4}});
  EXPECT_EQ(separate_coincident(g, 20.0), 2u);
  auto L = lay_out(g);
  auto q = measure_layout(g, L);
  EXPECT_EQ(q.octilinear_share, 1.0);
  EXPECT_EQ(q.crossings, 0u);
}

TEST(LayoutQuality, CountsWhatIsWrong) {
  auto g = graph({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{0, 2}, {1, 3}});
  Layout crossing;
  crossing.pos = g.pos;
  crossing.paths = {{{0, 0}, {10, 10}}, {{10, 0}, {0, 10}}};
  auto q = measure_layout(g, crossing);
  EXPECT_EQ(q.crossings, 1u);
  EXPECT_EQ(q.geo_crossings, 1u);
  EXPECT_EQ(q.added_crossings, 0u);
  // Edges 0-1 and 2-3 do not cross geographically; drawn crossing, the crossing is added.
  auto sides = graph({{0, 0}, {10, 0}, {0, 10}, {10, 10}}, {{0, 1}, {2, 3}});
  Layout twisted;
  twisted.pos = sides.pos;
  twisted.paths = {{{0, 0}, {5, 5}, {10, 0}}, {{0, 10}, {5, 5}, {10, 10}}};
  auto t = measure_layout(sides, twisted);
  EXPECT_EQ(t.geo_crossings, 0u);
  EXPECT_EQ(t.crossings, 1u);
  EXPECT_EQ(t.added_crossings, 1u);
  Layout skewed = crossing;
  skewed.paths[0] = {{0, 0}, {10, 3}, {10, 10}};  // a 16.7 degree segment
  EXPECT_EQ(measure_layout(g, skewed).octilinear_share, 0.5);
  EXPECT_EQ(measure_layout(g, skewed).bends, 1u);
}

}  // namespace
}  // namespace tourmap::metro
