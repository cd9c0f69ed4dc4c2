#pragma once
// The octilinear grid graph that route_octilinear draws on (after Bast, Brosi and Storandt,
// "Metro Maps on Octilinear Grid Graphs", 2020): nodes on a square grid, each joined to its 8
// neighbours, and what occupies them (stations, paths, the diagonals paths take). Internal to
// metro/octilinear_grid.cpp and its pieces.

#include "metro/layout_graph.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <vector>

namespace tourmap::metro::octi {

// Directions, counter-clockwise from east: 0 E, 1 NE, 2 N, 3 NW, 4 W, 5 SW, 6 S, 7 SE.
inline constexpr int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
inline constexpr int kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
inline constexpr int kNoDir = 8;  // a search state that has not moved yet
inline constexpr double kInf = std::numeric_limits<double>::infinity();

// The turn from direction a to direction b, in steps of 45 degrees (0..4).
inline int turn(int a, int b) {
  int d = std::abs(a - b) % 8;
  return std::min(d, 8 - d);
}

// Occupancy of a grid node (GridGraph::used).
enum : std::uint8_t { kFree = 0, kPath = 1, kStation = 2, kCrossing = 3 };

struct GridGraph {
  int w = 0, h = 0;
  XY origin;
  double cell = 1;
  std::vector<std::uint8_t> used;      // 0 free, 1 path, 2 station, 3 two paths crossing
  std::vector<std::uint8_t> diagonal;  // bit d: the diagonal move in direction d from here is taken
  std::vector<int> reserved_for;       // the station next to this node (its ports need the room), or -1
  std::vector<int> owner;              // the chain whose path runs through this node, or -1
  std::vector<std::int8_t> axis;       // direction % 4 of that path when it goes straight through, else -1
  std::vector<int> owner2;             // at a crossing: the second path...
  std::vector<std::int8_t> axis2;      // ...and its axis
  std::vector<int> diagonal_owner;     // 2 per node: the chain on the NE and the NW diagonal from it

  void resize(std::size_t nodes) {
    used.assign(nodes, 0);
    diagonal.assign(nodes, 0);
    reserved_for.assign(nodes, -1);
    owner.assign(nodes, -1);
    axis.assign(nodes, -1);
    owner2.assign(nodes, -1);
    axis2.assign(nodes, -1);
    diagonal_owner.assign(2 * nodes, -1);
  }

  int at(int x, int y) const { return y * w + x; }
  XY point(int node) const { return {origin.x + (node % w) * cell, origin.y + (node / w) * cell}; }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h; }
  // Where the owner of the diagonal from `node` in direction d (odd) is kept: NE and NW
  // diagonals at their lower end, SW and SE ones as the NE / NW diagonal they reverse.
  std::size_t diagonal_slot(int node, int d) const {
    int x = node % w, y = node / w;
    if (d == 1) return 2 * static_cast<std::size_t>(node);
    if (d == 3) return 2 * static_cast<std::size_t>(node) + 1;
    if (d == 5) return 2 * static_cast<std::size_t>(at(x - 1, y - 1));
    return 2 * static_cast<std::size_t>(at(x + 1, y - 1)) + 1;
  }
  // The diagonal from `node` in direction d crosses the other diagonal of the same cell: the
  // chain on that one, or -1 when it is free.
  int crossing_diagonal(int node, int d) const {
    if (d % 2 == 0) return -1;
    int x = node % w, y = node / w;
    // Cell corners: the crossing diagonal starts at (x + dx, y) going (-dx, dy).
    int cx = x + kDx[d], cy = y;
    if (!inside(cx, cy)) return -1;
    int cross = (d == 1) ? 3 : (d == 3) ? 1 : (d == 5) ? 7 : 5;
    if (!((diagonal[at(cx, cy)] >> cross) & 1)) return -1;
    return diagonal_owner[diagonal_slot(at(cx, cy), cross)];
  }
  bool crossing_taken(int node, int d) const { return crossing_diagonal(node, d) >= 0; }
  void take_diagonal(int node, int d, int chain) {
    if (d % 2 == 0) return;
    int x = node % w, y = node / w;
    diagonal[node] |= 1 << d;
    diagonal[at(x + kDx[d], y + kDy[d])] |= 1 << ((d + 4) % 8);
    diagonal_owner[diagonal_slot(node, d)] = chain;
  }
  void release_diagonal(int node, int d) {
    if (d % 2 == 0) return;
    int x = node % w, y = node / w;
    diagonal[node] &= static_cast<std::uint8_t>(~(1 << d));
    diagonal[at(x + kDx[d], y + kDy[d])] &= static_cast<std::uint8_t>(~(1 << ((d + 4) % 8)));
    diagonal_owner[diagonal_slot(node, d)] = -1;
  }
};

// A free grid of spacing `cell` over the bounding box of `points`, with `margin` cells of room
// on every side (around the origin when there are no points).
GridGraph grid_around(const std::vector<XY>& points, double cell, int margin);

// The direction of the step from grid node a to its neighbour b, or -1 when they are not neighbours.
int direction_between(const GridGraph& g, int a, int b);

}  // namespace tourmap::metro::octi
