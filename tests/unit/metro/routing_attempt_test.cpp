#include "metro/routing_attempt.hpp"

#include "metro/layout_quality.hpp"
#include "metro/prelayout.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tourmap::metro::octi {
namespace {

using namespace std::chrono_literals;

struct Network {
  LayoutGraph g;
  std::vector<XY> start;
  std::vector<bool> anchor;
  std::vector<Chain> chains;
  std::vector<std::vector<char>> geo_crossing;
};

Network network(std::vector<XY> pos, std::vector<std::pair<std::uint32_t, std::uint32_t>> edges,
                std::vector<std::vector<std::uint32_t>> lines) {
  Network n;
  n.g.pos = std::move(pos);
  n.g.edges = std::move(edges);
  n.g.edge_lines = std::move(lines);
  n.g.min_length.assign(n.g.edges.size(), 10.0);
  n.start = stress_layout(n.g, scale_to_lengths(n.g));
  n.chains = contract_chains(n.g, n.anchor);
  n.geo_crossing.assign(n.chains.size(), std::vector<char>(n.chains.size(), 0));
  return n;
}

// A plus of two lines through a hub (arms of two stations each), and a third line closing
// the north and east arms into a loop. In metres.
Network plus_with_loop() {
  return network({{0, 0}, {1000, 50}, {2000, 0}, {-50, 1000}, {0, 2000}, {-1000, 0}, {-2000, -60}, {30, -1000},
                  {0, -2000}, {1600, 1500}},
                 {{0, 1}, {1, 2}, {0, 3}, {3, 4}, {0, 5}, {5, 6}, {0, 7}, {7, 8}, {2, 9}, {9, 4}},
                 {{0}, {0}, {1}, {1}, {0}, {0}, {1}, {1}, {2}, {2}});
}

AttemptResult run(const Network& n, const GridRouteParams& p = {}, Clock::duration budget = 30s) {
  return RoutingAttempt(n.g, n.start, n.chains, n.anchor, n.geo_crossing, p, p.cell).run({}, Clock::now() + budget);
}

TEST(RoutingAttempt, SmallNetworkIsOctilinearWithoutCrossings) {
  auto n = plus_with_loop();
  ASSERT_EQ(n.chains.size(), 5u);  // four arms and the loop line
  auto r = run(n);
  EXPECT_EQ(r.failed, 0u);
  EXPECT_TRUE(r.failed_chains.empty());
  EXPECT_TRUE(r.out_of_order_chains.empty());
  EXPECT_EQ(r.overlapping, 0u);
  EXPECT_EQ(r.crossing_routes, 0u);
  EXPECT_FALSE(r.timed_out);
  EXPECT_GT(r.grid_nodes, 0u);
  auto q = measure_layout(n.g, r.layout);
  EXPECT_EQ(q.octilinear_share, 1.0);
  EXPECT_EQ(q.crossings, 0u);
  EXPECT_EQ(q.order_violations, 0u);
  // Every edge's path runs between its stations, anchors on grid nodes (whole cells apart).
  for (std::size_t e = 0; e < n.g.edges.size(); ++e) {
    const auto& path = r.layout.paths[e];
    ASSERT_GE(path.size(), 2u);
    EXPECT_EQ(path.front().x, r.layout.pos[n.g.edges[e].first].x) << e;
    EXPECT_EQ(path.front().y, r.layout.pos[n.g.edges[e].first].y) << e;
    EXPECT_EQ(path.back().x, r.layout.pos[n.g.edges[e].second].x) << e;
    EXPECT_EQ(path.back().y, r.layout.pos[n.g.edges[e].second].y) << e;
  }
  for (std::uint32_t v = 0; v < n.g.pos.size(); ++v)
    if (n.anchor[v]) {
      const double dx = r.layout.pos[v].x - r.layout.pos[0].x, dy = r.layout.pos[v].y - r.layout.pos[0].y;
      EXPECT_NEAR(dx, std::round(dx), 1e-9) << v;
      EXPECT_NEAR(dy, std::round(dy), 1e-9) << v;
    }
}

TEST(RoutingAttempt, HubKeepsItsCircularOrder) {
  auto n = plus_with_loop();
  auto r = run(n);
  // Around the hub (station 0): east, north, west, south arms leave in that order.
  std::vector<double> angles;
  for (std::uint32_t e : {0u, 2u, 4u, 6u}) {
    const auto& path = r.layout.paths[e];
    angles.push_back(std::atan2(path[1].y - path[0].y, path[1].x - path[0].x));
  }
  EXPECT_NEAR(angles[0], 0.0, 1e-9);
  EXPECT_NEAR(angles[1], M_PI / 2, 1e-9);
  EXPECT_NEAR(std::abs(angles[2]), M_PI, 1e-9);
  EXPECT_NEAR(angles[3], -M_PI / 2, 1e-9);
}

TEST(RoutingAttempt, GeographicCrossingIsKeptOnce) {
  // Two single-edge lines that cross without a station: allowed to cross once.
  auto n = network({{0, 0}, {2000, 0}, {1000, -1000}, {1000, 1000}}, {{0, 1}, {2, 3}}, {{0}, {1}});
  n.anchor.assign(4, true);
  n.chains = contract_chains(n.g, n.anchor);
  ASSERT_EQ(n.chains.size(), 2u);
  n.geo_crossing = {{0, 1}, {1, 0}};
  auto r = run(n);
  EXPECT_EQ(r.failed, 0u);
  EXPECT_EQ(r.crossing_routes, 0u);
  auto q = measure_layout(n.g, r.layout);
  EXPECT_EQ(q.octilinear_share, 1.0);
  EXPECT_EQ(q.crossings, 1u);
  EXPECT_EQ(q.added_crossings, 0u);
}

TEST(RoutingAttempt, PastDeadlineOnlyTheLastResortRoutes) {
  // Past the deadline the negotiating and the crossing passes route nothing; the last-resort
  // pass (through other paths) has no deadline of its own and still routes every chain, so
  // each counts as overlapping. (What the code does today: a time-out shows as "overlapping".)
  auto n = plus_with_loop();
  auto r = run(n, {}, -1s);
  EXPECT_TRUE(r.timed_out);
  EXPECT_EQ(r.ripups, 0u);
  EXPECT_EQ(r.crossing_routes, 0u);
  EXPECT_EQ(r.overlapping, n.chains.size());
  EXPECT_EQ(r.failed, 0u);
  auto q = measure_layout(n.g, r.layout);
  EXPECT_EQ(q.octilinear_share, 1.0);
}

TEST(RoutingAttempt, NinthEdgeOfAStationIsDrawnStraight) {
  // A hub with 9 spokes has 8 ports: one spoke has no route at all.
  std::vector<XY> pos = {{0, 0}};
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::uint32_t i = 1; i <= 9; ++i) {
    const double a = 2 * M_PI * (i - 1) / 9;
    pos.push_back({1500 * std::cos(a), 1500 * std::sin(a)});
    edges.push_back({0, i});
  }
  auto n = network(pos, edges, std::vector<std::vector<std::uint32_t>>(9, {0}));
  ASSERT_EQ(n.chains.size(), 9u);
  auto r = run(n);
  EXPECT_EQ(r.failed, 1u);
  ASSERT_EQ(r.failed_chains.size(), 1u);
  int octilinear = 0;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto& path = r.layout.paths[e];
    ASSERT_GE(path.size(), 2u);
    EXPECT_EQ(path.front().x, r.layout.pos[0].x);
    EXPECT_EQ(path.front().y, r.layout.pos[0].y);
    bool octi = true;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      const double dx = std::abs(path[i + 1].x - path[i].x), dy = std::abs(path[i + 1].y - path[i].y);
      octi = octi && (dx < 1e-9 || dy < 1e-9 || std::abs(dx - dy) < 1e-9);
    }
    octilinear += octi;
  }
  EXPECT_EQ(octilinear, 8);
  // The failed spoke is one straight segment.
  EXPECT_EQ(r.layout.paths[n.chains[r.failed_chains[0]].edges[0]].size(), 2u);
}

TEST(RoutingAttempt, InteriorStationsLieOnTheirChainsPath) {
  auto n = plus_with_loop();
  auto r = run(n);
  // The loop line 2-9-4: station 9 is interior; its two edges meet there.
  ASSERT_FALSE(n.anchor[9]);
  EXPECT_EQ(r.layout.paths[8].back().x, r.layout.pos[9].x);
  EXPECT_EQ(r.layout.paths[9].front().x, r.layout.pos[9].x);
  EXPECT_EQ(r.layout.paths[9].front().y, r.layout.pos[9].y);
}

// A hub with four arms whose start positions (from a pre-layout) are not in the geographic
// order of the arms: east, north, west, south geographically, but north, east, west, south
// in the start. Without a price on the order, the router follows the start and breaks the
// order, and reports the chains it routed out of order, so that route_octilinear routes them
// first in its next attempt.
TEST(RoutingAttempt, ChainsRoutedOutOfOrderAreReported) {
  auto n = network({{0, 0}, {1500, 0}, {0, 1500}, {-1500, 0}, {0, -1500}}, {{0, 1}, {0, 2}, {0, 3}, {0, 4}},
                   {{0}, {1}, {2}, {3}});
  n.start = {{0, 0}, {0, 15}, {15, 0}, {-15, 0}, {0, -15}};
  GridRouteParams free_order;
  free_order.order_penalty = 0;
  free_order.port_plan_weight = 0;
  auto broken = run(n, free_order);
  EXPECT_GT(measure_layout(n.g, broken.layout).order_violations, 0u);
  EXPECT_FALSE(broken.out_of_order_chains.empty());
}

}  // namespace
}  // namespace tourmap::metro::octi
