#include "metro/grid_router.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace tourmap::metro::octi {
namespace {

// A 21 x 21 grid of unit cells (corners 0..20).
GridGraph grid21() {
  auto grid = grid_around({{0, 0}, {10, 10}}, 1.0, 5);
  EXPECT_EQ(grid.w, 21);
  EXPECT_EQ(grid.h, 21);
  return grid;
}

// One fixed grid node as the end of a search, every port allowed at no cost.
Endpoint fixed(const GridGraph& grid, int x, int y, int station) {
  Endpoint ep;
  ep.station = station;
  ep.nodes = {{grid.at(x, y), 0.0}};
  ep.allowed.fill(true);
  ep.port_cost.fill(0.0);
  ep.centre = {static_cast<double>(x), static_cast<double>(y)};
  ep.radius = 0;
  return ep;
}

std::vector<int> directions(const GridGraph& grid, const std::vector<int>& path) {
  std::vector<int> dirs;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) dirs.push_back(direction_between(grid, path[i], path[i + 1]));
  return dirs;
}

// The turns along a path (0..4 steps of 45 degrees), one per interior node that bends.
std::vector<int> bends(const GridGraph& grid, const std::vector<int>& path) {
  auto dirs = directions(grid, path);
  std::vector<int> out;
  for (std::size_t i = 0; i + 1 < dirs.size(); ++i)
    if (dirs[i] != dirs[i + 1]) out.push_back(turn(dirs[i], dirs[i + 1]));
  return out;
}

TEST(GridRouter, StraightPathHasNoBends) {
  auto grid = grid21();
  GridRouteParams p;
  GridRouter router(grid, p);
  auto path = router.route(fixed(grid, 3, 10, 0), fixed(grid, 15, 10, 1));
  ASSERT_EQ(path.size(), 13u);
  EXPECT_EQ(path.front(), grid.at(3, 10));
  EXPECT_EQ(path.back(), grid.at(15, 10));
  EXPECT_TRUE(bends(grid, path).empty());
  for (int d : directions(grid, path)) EXPECT_EQ(d, 0);  // east
  // Diagonal too.
  path = router.route(fixed(grid, 2, 2, 0), fixed(grid, 12, 12, 1));
  ASSERT_EQ(path.size(), 11u);
  EXPECT_TRUE(bends(grid, path).empty());
}

TEST(GridRouter, BendCostsDecideBetweenBends) {
  // From (2, 2) to (8, 6): 4 diagonal steps and 2 straight ones with one 45-degree bend
  // (length 7.66), or 5 north-east and 1 south-east with one 90-degree bend (length 8.49).
  // Either way 6 steps.
  auto grid = grid21();
  GridRouteParams p;
  {
    GridRouter router(grid, p);  // defaults: 45 degrees cost 1, 90 degrees 2.5
    auto path = router.route(fixed(grid, 2, 2, 0), fixed(grid, 8, 6, 1));
    EXPECT_EQ(bends(grid, path), (std::vector<int>{1}));
    EXPECT_EQ(path.size(), 7u);
  }
  p.bend_cost = {0.0, 100.0, 1.0, 6.0};  // a 45-degree bend now costs more than the detour
  {
    GridRouter router(grid, p);
    auto path = router.route(fixed(grid, 2, 2, 0), fixed(grid, 8, 6, 1));
    EXPECT_EQ(bends(grid, path), (std::vector<int>{2}));
    EXPECT_EQ(path.size(), 7u);
  }
}

TEST(GridRouter, PortCostsChooseTheWayOut) {
  auto grid = grid21();
  GridRouteParams p;
  GridRouter router(grid, p);
  auto src = fixed(grid, 3, 10, 0);
  src.allowed.fill(false);
  src.allowed[2] = true;  // north only
  auto path = router.route(src, fixed(grid, 15, 10, 1));
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(direction_between(grid, path[0], path[1]), 2);
  src.allowed.fill(true);
  src.port_cost.fill(50.0);
  src.port_cost[6] = 0.0;  // south is cheap
  path = router.route(src, fixed(grid, 15, 10, 1));
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(direction_between(grid, path[0], path[1]), 6);
}

TEST(GridRouter, OccupiedNodesAreAvoided) {
  auto grid = grid21();
  // A station wall at x = 9 from y = 4 to 16: the path goes round it.
  for (int y = 4; y <= 16; ++y) grid.used[grid.at(9, y)] = kStation;
  GridRouteParams p;
  GridRouter router(grid, p);
  auto path = router.route(fixed(grid, 3, 10, 0), fixed(grid, 15, 10, 1));
  ASSERT_FALSE(path.empty());
  EXPECT_EQ(path.front(), grid.at(3, 10));
  EXPECT_EQ(path.back(), grid.at(15, 10));
  for (int node : path) EXPECT_EQ(grid.used[node], kFree);
  for (std::size_t i = 0; i + 1 < path.size(); ++i) EXPECT_GE(direction_between(grid, path[i], path[i + 1]), 0);
  // Walled off completely: no path.
  for (int y = 0; y < grid.h; ++y) grid.used[grid.at(9, y)] = kStation;
  EXPECT_TRUE(router.route(fixed(grid, 3, 10, 0), fixed(grid, 15, 10, 1)).empty());
}

TEST(GridRouter, WalledInEndFailsWithoutASearch) {
  // A 201 x 201 grid; the target inside a ring of stations: no state is expanded (the search
  // would otherwise spend its cap on the rest of the grid).
  auto grid = grid_around({{0, 0}, {200, 200}}, 1.0, 0);
  for (int x = 148; x <= 152; ++x)
    for (int y = 148; y <= 152; ++y)
      if (x == 148 || x == 152 || y == 148 || y == 152) grid.used[grid.at(x, y)] = kStation;
  GridRouteParams p;
  GridRouter router(grid, p);
  EXPECT_TRUE(router.route(fixed(grid, 20, 20, 0), fixed(grid, 150, 150, 1)).empty());
  EXPECT_EQ(router.expansions(), 0u);
  // The source walled in instead.
  EXPECT_TRUE(router.route(fixed(grid, 150, 150, 1), fixed(grid, 20, 20, 0)).empty());
  EXPECT_EQ(router.expansions(), 0u);
  // A gap in the ring: routed.
  grid.used[grid.at(152, 150)] = kFree;
  EXPECT_FALSE(router.route(fixed(grid, 20, 20, 0), fixed(grid, 150, 150, 1)).empty());
  EXPECT_GT(router.expansions(), 0u);
}

TEST(GridRouter, RingOfCrossablePathIsNotAWall) {
  // The target inside a ring of chain 0's path, straight on every side (corners bend): it
  // can be reached across it only where chain 0 may be crossed.
  auto grid = grid21();
  for (int x = 12; x <= 18; ++x)
    for (int y = 12; y <= 18; ++y) {
      const bool side_x = x == 12 || x == 18, side_y = y == 12 || y == 18;
      if (!side_x && !side_y) continue;
      const int n = grid.at(x, y);
      grid.used[n] = kPath;
      grid.owner[n] = 0;
      grid.axis[n] = side_x && side_y ? -1 : side_x ? 2 : 0;
    }
  GridRouteParams p;
  GridRouter router(grid, p);
  std::vector<char> crossable = {0, 0};
  router.allow_crossing(&crossable, false);
  EXPECT_TRUE(router.route(fixed(grid, 3, 3, 1), fixed(grid, 15, 15, 2)).empty());
  EXPECT_EQ(router.expansions(), 0u);
  crossable[0] = 1;
  auto path = router.route(fixed(grid, 3, 3, 1), fixed(grid, 15, 15, 2));
  ASSERT_FALSE(path.empty());
  EXPECT_EQ(path.back(), grid.at(15, 15));
}

TEST(GridRouter, TakenDiagonalIsNotCrossed) {
  auto grid = grid21();
  // A path of chain 0 on the NW diagonals of a column of cells (x 9..10), every row: the
  // crossing NE diagonals are closed; a path to the north-east crosses the column straight.
  for (int y = 0; y + 1 < grid.h; ++y) grid.take_diagonal(grid.at(10, y), 3, 0);
  EXPECT_TRUE(grid.crossing_taken(grid.at(9, 5), 1));
  EXPECT_FALSE(grid.crossing_taken(grid.at(9, 5), 0));
  GridRouteParams p;
  GridRouter router(grid, p);
  auto path = router.route(fixed(grid, 5, 3, 0), fixed(grid, 15, 13, 1));
  ASSERT_FALSE(path.empty());
  for (std::size_t i = 0; i + 1 < path.size(); ++i)
    EXPECT_FALSE(grid.crossing_taken(path[i], direction_between(grid, path[i], path[i + 1])));
}

TEST(GridRouter, PathsCrossOnlyWhenAllowedAndStraightOver) {
  auto grid = grid21();
  // Chain 0 runs north through x = 9, every row.
  for (int y = 0; y < grid.h; ++y) {
    grid.used[grid.at(9, y)] = kPath;
    grid.owner[grid.at(9, y)] = 0;
    grid.axis[grid.at(9, y)] = 2;
  }
  GridRouteParams p;
  GridRouter router(grid, p);
  std::vector<char> crossable = {0, 0};
  router.allow_crossing(&crossable, false);
  EXPECT_TRUE(router.route(fixed(grid, 3, 10, 1), fixed(grid, 15, 10, 2)).empty());
  crossable[0] = 1;  // chain 0 crosses this one geographically
  // 6 east and 6 north-east: a path with one bend would bend on x = 9, on chain 0's path. It
  // must cross straight over, so it bends twice, off chain 0.
  auto path = router.route(fixed(grid, 3, 10, 1), fixed(grid, 15, 16, 2));
  ASSERT_FALSE(path.empty());
  int on_other = 0;
  for (std::size_t i = 1; i + 1 < path.size(); ++i)
    if (grid.used[path[i]] == kPath) {
      ++on_other;
      EXPECT_EQ(direction_between(grid, path[i - 1], path[i]), direction_between(grid, path[i], path[i + 1]));
    }
  EXPECT_EQ(on_other, 1);
  EXPECT_EQ(bends(grid, path), (std::vector<int>{1, 1}));
  // Any chain, as the fallback.
  crossable[0] = 0;
  router.allow_crossing(&crossable, true);
  EXPECT_FALSE(router.route(fixed(grid, 3, 10, 1), fixed(grid, 15, 10, 2)).empty());
}

TEST(GridRouter, NegotiationAndOverlapGoThroughPaths) {
  auto grid = grid21();
  // Chain 0 runs through x = 9, bending at every node (no axis): it cannot be crossed.
  for (int y = 0; y < grid.h; ++y) {
    grid.used[grid.at(9, y)] = kPath;
    grid.owner[grid.at(9, y)] = 0;
    grid.axis[grid.at(9, y)] = -1;  // bending: no straight crossing anywhere
  }
  GridRouteParams p;
  GridRouter router(grid, p);
  EXPECT_TRUE(router.route(fixed(grid, 3, 10, 1), fixed(grid, 15, 10, 2)).empty());
  std::vector<float> history(grid.used.size(), 0.0f);
  router.set_history(&history);
  router.set_negotiation(true);
  EXPECT_FALSE(router.route(fixed(grid, 3, 10, 1), fixed(grid, 15, 10, 2)).empty());
  router.set_negotiation(false);
  router.allow_overlap(true);
  EXPECT_FALSE(router.route(fixed(grid, 3, 10, 1), fixed(grid, 15, 10, 2)).empty());
  router.allow_overlap(false);
  EXPECT_TRUE(router.route(fixed(grid, 3, 10, 1), fixed(grid, 15, 10, 2)).empty());
}

TEST(GridRouter, StationsAreNeverPassed) {
  auto grid = grid21();
  for (int y = 0; y < grid.h; ++y) grid.used[grid.at(9, y)] = kStation;
  GridRouteParams p;
  GridRouter router(grid, p);
  std::vector<float> history(grid.used.size(), 0.0f);
  router.set_history(&history);
  router.set_negotiation(true);
  EXPECT_TRUE(router.route(fixed(grid, 3, 10, 1), fixed(grid, 15, 10, 2)).empty());
  router.set_negotiation(false);
  router.allow_overlap(true);
  EXPECT_TRUE(router.route(fixed(grid, 3, 10, 1), fixed(grid, 15, 10, 2)).empty());
}

TEST(GridRouter, NegotiationPrefersNodesFoughtOverLess) {
  auto grid = grid21();
  for (int y = 0; y < grid.h; ++y) {
    grid.used[grid.at(9, y)] = kPath;
    grid.owner[grid.at(9, y)] = 0;
    grid.axis[grid.at(9, y)] = -1;
  }
  GridRouteParams p;
  GridRouter router(grid, p);
  std::vector<float> history(grid.used.size(), 0.0f);
  history[grid.at(9, 10)] = 50.0f;  // the straight way through is expensive now
  router.set_history(&history);
  router.set_negotiation(true);
  auto path = router.route(fixed(grid, 3, 10, 1), fixed(grid, 15, 10, 2));
  ASSERT_FALSE(path.empty());
  EXPECT_EQ(std::find(path.begin(), path.end(), grid.at(9, 10)), path.end());
}

TEST(GridRouter, ReservedNodesCostExtra) {
  auto grid = grid21();
  // Nodes next to station 7 on the straight line: a small detour is cheaper than passing.
  for (int x = 8; x <= 10; ++x) grid.reserved_for[grid.at(x, 10)] = 7;
  GridRouteParams p;
  p.reserved_penalty = 100;
  GridRouter router(grid, p);
  auto path = router.route(fixed(grid, 3, 10, 0), fixed(grid, 15, 10, 1));
  ASSERT_FALSE(path.empty());
  for (int node : path) EXPECT_NE(grid.reserved_for[node], 7);
  // The path's own end station may be passed next to.
  path = router.route(fixed(grid, 3, 10, 7), fixed(grid, 15, 10, 1));
  EXPECT_EQ(path.size(), 13u);
}

TEST(GridRouter, LoopsAreCutOut) {
  EXPECT_EQ(without_loops({1, 2, 3, 4, 2, 5}), (std::vector<int>{1, 2, 5}));
  EXPECT_EQ(without_loops({1, 2, 3}), (std::vector<int>{1, 2, 3}));
}

}  // namespace
}  // namespace tourmap::metro::octi
