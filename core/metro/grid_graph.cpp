#include "metro/grid_graph.hpp"

#include <cmath>

namespace tourmap::metro::octi {

GridGraph grid_around(const std::vector<XY>& points, double cell, int margin) {
  double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  for (const auto& q : points) {
    x0 = std::min(x0, q.x);
    y0 = std::min(y0, q.y);
    x1 = std::max(x1, q.x);
    y1 = std::max(y1, q.y);
  }
  if (points.empty()) x0 = y0 = x1 = y1 = 0;
  GridGraph grid;
  grid.cell = cell;
  grid.origin = {x0 - margin * cell, y0 - margin * cell};
  grid.w = static_cast<int>(std::ceil((x1 - x0) / cell)) + 2 * margin + 1;
  grid.h = static_cast<int>(std::ceil((y1 - y0) / cell)) + 2 * margin + 1;
  grid.resize(static_cast<std::size_t>(grid.w) * grid.h);
  return grid;
}

int direction_between(const GridGraph& g, int a, int b) {
  int dx = b % g.w - a % g.w, dy = b / g.w - a / g.w;
  for (int d = 0; d < 8; ++d)
    if (kDx[d] == dx && kDy[d] == dy) return d;
  return -1;
}

}  // namespace tourmap::metro::octi
