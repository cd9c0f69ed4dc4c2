#include "metro/port_planning.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

namespace tourmap::metro::octi {
namespace {

// Geographic directions as atan2 gives them, in (-pi, pi].
std::vector<double> normalised(std::vector<double> angles) {
  for (auto& a : angles) a = std::atan2(std::sin(a), std::cos(a));
  return angles;
}

bool distinct(const std::vector<int>& ports) { return std::set<int>(ports.begin(), ports.end()).size() == ports.size(); }

// The ports, taken in the order of their edges' angles, go once round counter-clockwise.
bool in_circular_order(const std::vector<double>& angles, const std::vector<int>& ports) {
  std::vector<std::size_t> order(angles.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return angles[a] < angles[b]; });
  int turns = 0;
  for (std::size_t i = 0; i < order.size(); ++i) {
    int gap = (ports[order[(i + 1) % order.size()]] - ports[order[i]] + 8) % 8;
    if (order.size() > 1 && gap == 0) return false;
    turns += gap;
  }
  return order.size() <= 1 || turns == 8;
}

TEST(PortPlanning, RegularFourWayStationGetsTheAxes) {
  auto angles = normalised({0, M_PI / 2, M_PI, 3 * M_PI / 2});
  EXPECT_EQ(plan_ports(angles), (std::vector<int>{0, 2, 4, 6}));
}

TEST(PortPlanning, SingleEdgeTakesTheNearestDirection) {
  EXPECT_EQ(plan_ports({0.3}), (std::vector<int>{0}));
  EXPECT_EQ(plan_ports({0.5}), (std::vector<int>{1}));  // nearer 45 than 0 degrees
  EXPECT_EQ(plan_ports({-2.9}), (std::vector<int>{4}));
}

TEST(PortPlanning, SkewedFourWayStationKeepsItsOrder) {
  auto angles = normalised({0.1, 1.4, 3.0, 4.6});
  auto ports = plan_ports(angles);
  ASSERT_EQ(ports.size(), 4u);
  EXPECT_TRUE(distinct(ports));
  EXPECT_TRUE(in_circular_order(angles, ports));
  EXPECT_EQ(ports, (std::vector<int>{0, 2, 4, 6}));
}

TEST(PortPlanning, FiveWayStationGetsDistinctPortsInOrder) {
  auto angles = normalised({0.1, 1.2, 2.0, 3.5, 5.0});
  auto ports = plan_ports(angles);
  ASSERT_EQ(ports.size(), 5u);
  EXPECT_TRUE(distinct(ports));
  EXPECT_TRUE(in_circular_order(angles, ports));
  // Each port within 45 degrees of its edge (there is room for all of them).
  for (std::size_t i = 0; i < angles.size(); ++i) {
    double d = std::fmod(std::abs(angles[i] - ports[i] * M_PI / 4), 2 * M_PI);
    EXPECT_LE(std::min(d, 2 * M_PI - d), M_PI / 4 + 1e-9) << i;
  }
}

TEST(PortPlanning, CrowdedEdgesAreSpreadOverDistinctPorts) {
  // Five edges within 25 degrees of east: they cannot all point east.
  std::vector<double> angles = {0.4, 0.0, 0.2, -0.2, 0.1};
  auto ports = plan_ports(angles);
  EXPECT_TRUE(distinct(ports));
  EXPECT_TRUE(in_circular_order(angles, ports));
  // Sorted by angle (-0.2 ... 0.4 rad) they get S, SE, E, NE, N: the least total deviation
  // puts the middle edge (0.1 rad) on east.
  EXPECT_EQ(ports, (std::vector<int>{2, 7, 1, 6, 0}));
}

TEST(PortPlanning, EightEdgesUseEveryPort) {
  std::vector<double> angles;
  for (int i = 0; i < 8; ++i) angles.push_back(std::atan2(std::sin(i * 0.7 + 0.05 * i * i), std::cos(i * 0.7 + 0.05 * i * i)));
  auto ports = plan_ports(angles);
  EXPECT_TRUE(distinct(ports));
  EXPECT_TRUE(in_circular_order(angles, ports));
  EXPECT_EQ(*std::min_element(ports.begin(), ports.end()), 0);
  EXPECT_EQ(*std::max_element(ports.begin(), ports.end()), 7);
}

TEST(PortPlanning, MoreThanEightEdgesHaveNoPlan) {
  std::vector<double> angles;
  for (int i = 0; i < 9; ++i) angles.push_back(-M_PI + 2 * M_PI * i / 9);
  EXPECT_EQ(plan_ports(angles), std::vector<int>(9, -1));
  EXPECT_TRUE(plan_ports({}).empty());
}

TEST(PortPlanning, ChainPortsArePlannedPerStation) {
  // A hub with four spokes (E, N, W, S), one spoke two edges long.
  LayoutGraph g;
  g.pos = {{0, 0}, {100, 0}, {0, 100}, {-100, 0}, {0, -100}, {0, -200}};
  g.edges = {{0, 1}, {2, 0}, {0, 3}, {0, 4}, {4, 5}};
  g.edge_lines.assign(5, {0});
  g.min_length.assign(5, 10);
  std::vector<bool> anchor;
  auto chains = contract_chains(g, anchor);
  ASSERT_EQ(chains.size(), 4u);
  auto planned = plan_chain_ports(g, chains);
  auto angles = chain_end_angles(g, chains);
  ASSERT_EQ(angles[0].size(), 4u);
  ASSERT_EQ(angles[5].size(), 1u);
  EXPECT_TRUE(angles[4].empty());  // inside a chain
  std::vector<int> hub_ports;
  for (std::size_t ci = 0; ci < chains.size(); ++ci) {
    const auto& c = chains[ci];
    int at_hub = c.nodes.front() == 0 ? planned[ci][0] : planned[ci][1];
    int at_end = c.nodes.front() == 0 ? planned[ci][1] : planned[ci][0];
    hub_ports.push_back(at_hub);
    EXPECT_EQ(at_end, (at_hub + 4) % 8) << ci;  // a spoke's far end looks back at the hub
  }
  std::sort(hub_ports.begin(), hub_ports.end());
  EXPECT_EQ(hub_ports, (std::vector<int>{0, 2, 4, 6}));
}

TEST(PortPlanning, OrderCheckRejectsAPortOutOfCircularOrder) {
  // East and west are routed (ports 0 and 4); north comes next.
  std::vector<std::pair<int, double>> taken = {{0, 0.0}, {4, M_PI}};
  std::vector<double> all = {0.0, M_PI, M_PI / 2};
  EXPECT_TRUE(keeps_circular_order(taken, all, M_PI / 2, 2));
  EXPECT_TRUE(keeps_circular_order(taken, all, M_PI / 2, 1));
  EXPECT_FALSE(keeps_circular_order(taken, all, M_PI / 2, 6));  // south: between west and east
  EXPECT_FALSE(keeps_circular_order(taken, all, M_PI / 2, 0));  // taken... and no gap left
}

TEST(PortPlanning, OrderCheckLeavesRoomForPendingEdges) {
  // East is routed on port 0; an edge at 0.3 rad is still to come: the edge at 0.6 rad may not
  // take port 1 (no port would be left between them), but port 2 leaves port 1 free.
  std::vector<std::pair<int, double>> taken = {{0, 0.0}};
  std::vector<double> all = {0.0, 0.3, 0.6};
  EXPECT_FALSE(keeps_circular_order(taken, all, 0.6, 1));
  EXPECT_TRUE(keeps_circular_order(taken, all, 0.6, 2));
  // Without the pending edge, port 1 is fine.
  EXPECT_TRUE(keeps_circular_order(taken, {0.0, 0.6}, 0.6, 1));
}

TEST(PortPlanning, FirstEdgeMayTakeAnyPort) {
  for (int d = 0; d < 8; ++d) EXPECT_TRUE(keeps_circular_order({}, {1.0}, 1.0, d)) << d;
}

}  // namespace
}  // namespace tourmap::metro::octi
