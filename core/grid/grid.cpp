#include "grid/grid.hpp"

#include "util/stop.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tourmap::grid {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// Counts of points per finest-level cell as a summed-area table: O(1) counts for any quad.
class CellCounts {
 public:
  CellCounts(int width, int height)
      : w_(width), h_(height), sum_(static_cast<std::size_t>(width + 1) * static_cast<std::size_t>(height + 1), 0) {}
  void add(int x, int y) { ++sum_[index(x + 1, y + 1)]; }
  void finish() {
    for (int y = 1; y <= h_; ++y)
      for (int x = 1; x <= w_; ++x)
        sum_[index(x, y)] += sum_[index(x - 1, y)] + sum_[index(x, y - 1)] - sum_[index(x - 1, y - 1)];
  }
  // Points in cells [x0, x1) x [y0, y1).
  std::int64_t count(int x0, int y0, int x1, int y1) const {
    return sum_[index(x1, y1)] - sum_[index(x0, y1)] - sum_[index(x1, y0)] + sum_[index(x0, y0)];
  }

 private:
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * (w_ + 1) + x; }
  int w_, h_;
  std::vector<std::int32_t> sum_;  // point counts fit: callers pass fewer than 2^31 points
};

struct Lattice {
  int depth;        // levels below base
  int width, height;  // finest cells
  XY origin;
  double unit;      // finest cell size

  int cells_per_side(int level) const { return 1 << (depth - level); }
  std::pair<int, int> cell_of(XY p) const {
    int x = static_cast<int>(std::floor((p.x - origin.x) / unit));
    int y = static_cast<int>(std::floor((p.y - origin.y) / unit));
    return {std::clamp(x, 0, width - 1), std::clamp(y, 0, height - 1)};
  }
};

// Level of the leaf covering each finest cell: the quadtree, flattened.
class LeafLevels {
 public:
  explicit LeafLevels(const Lattice& lat) : lat_(lat), level_(static_cast<std::size_t>(lat.width) * lat.height, 0) {}
  int at(int x, int y) const { return level_[static_cast<std::size_t>(y) * lat_.width + x]; }
  void set(int x0, int y0, int size, int level) {
    for (int y = y0; y < y0 + size; ++y)
      std::fill_n(level_.begin() + static_cast<std::ptrdiff_t>(y) * lat_.width + x0, size, level);
  }
  struct Leaf {
    int x, y, level;  // lower-left finest cell and level
  };
  std::vector<Leaf> leaves() const {
    std::vector<Leaf> out;
    for (int y = 0; y < lat_.height; ++y)
      for (int x = 0; x < lat_.width; ++x) {
        int level = at(x, y), s = lat_.cells_per_side(level);
        if (x % s == 0 && y % s == 0) out.push_back({x, y, level});
      }
    return out;
  }

 private:
  const Lattice& lat_;
  std::vector<int> level_;
};

// Restricted quadtree: split every leaf with an edge neighbour more than one level finer.
void balance(LeafLevels& levels, const Lattice& lat) {
  bool changed = true;
  while (changed) {
    util::check_stop();  // each pass visits every leaf
    changed = false;
    for (const auto& leaf : levels.leaves()) {
      if (leaf.level >= lat.depth) continue;
      int s = lat.cells_per_side(leaf.level);
      bool split = false;
      for (int i = 0; i < s && !split; ++i) {
        const int xs[4] = {leaf.x + i, leaf.x + s, leaf.x + i, leaf.x - 1};
        const int ys[4] = {leaf.y - 1, leaf.y + i, leaf.y + s, leaf.y + i};
        for (int k = 0; k < 4 && !split; ++k)
          if (xs[k] >= 0 && xs[k] < lat.width && ys[k] >= 0 && ys[k] < lat.height)
            split = levels.at(xs[k], ys[k]) > leaf.level + 1;
      }
      if (split) {
        levels.set(leaf.x, leaf.y, s, leaf.level + 1);
        changed = true;
      }
    }
  }
}

Grid assemble(const Frame& frame, const Lattice& lat, const LeafLevels& levels) {
  Grid g;
  g.origin = frame.origin;
  g.cell = frame.cell;
  g.cols = frame.cols;
  g.rows = frame.rows;
  g.max_level = lat.depth;

  const int vw = lat.width + 1;
  std::vector<std::uint32_t> vertex_at(static_cast<std::size_t>(vw) * (lat.height + 1), kNone);
  auto vertex = [&](int x, int y) {
    auto& slot = vertex_at[static_cast<std::size_t>(y) * vw + x];
    if (slot == kNone) {
      slot = static_cast<std::uint32_t>(g.vertices.size());
      g.vertices.push_back({lat.origin.x + x * lat.unit, lat.origin.y + y * lat.unit});
      g.on_boundary.push_back(x == 0 || y == 0 || x == lat.width || y == lat.height);
    }
    return slot;
  };
  auto existing = [&](int x, int y) { return vertex_at[static_cast<std::size_t>(y) * vw + x]; };

  auto leaves = levels.leaves();
  g.cell_quad.assign(static_cast<std::size_t>(lat.width) * lat.height, kNone);
  for (const auto& leaf : leaves) {
    int s = lat.cells_per_side(leaf.level);
    Quad q;
    q.corners = {vertex(leaf.x, leaf.y), vertex(leaf.x + s, leaf.y), vertex(leaf.x + s, leaf.y + s),
                 vertex(leaf.x, leaf.y + s)};
    q.level = leaf.level;
    q.min = g.vertices[q.corners[0]];
    q.size = s * lat.unit;
    auto index = static_cast<std::uint32_t>(g.quads.size());
    for (int y = leaf.y; y < leaf.y + s; ++y)
      std::fill_n(g.cell_quad.begin() + static_cast<std::ptrdiff_t>(y) * lat.width + leaf.x, s, index);
    g.quads.push_back(q);
  }

  // Sides: link consecutive vertices along every quad side; a side's midpoint vertex, when a
  // finer neighbour created it, is a T-junction of this quad.
  g.neighbors.assign(g.vertices.size(), {});
  auto link = [&](std::uint32_t a, std::uint32_t b, Direction a_to_b, Direction b_to_a) {
    g.neighbors[a][a_to_b] = {Neighbor::Kind::vertex, b};
    g.neighbors[b][b_to_a] = {Neighbor::Kind::vertex, a};
  };
  for (std::uint32_t qi = 0; qi < g.quads.size(); ++qi) {
    const auto& leaf = leaves[qi];
    int s = lat.cells_per_side(leaf.level);
    const auto& c = g.quads[qi].corners;
    // side k runs from corner k to corner k+1; its midpoint in lattice coordinates:
    const int mx[4] = {leaf.x + s / 2, leaf.x + s, leaf.x + s / 2, leaf.x};
    const int my[4] = {leaf.y, leaf.y + s / 2, leaf.y + s, leaf.y + s / 2};
    // direction from the first to the second vertex of each side, and back
    const Direction fwd[4] = {kRight, kUp, kLeft, kDown};
    const Direction back[4] = {kLeft, kDown, kRight, kUp};
    const Direction inward[4] = {kUp, kLeft, kDown, kRight};  // from the side into the quad
    for (int k = 0; k < 4; ++k) {
      std::uint32_t a = c[k], b = c[(k + 1) % 4];
      std::uint32_t mid = s >= 2 ? existing(mx[k], my[k]) : kNone;
      if (mid == kNone) {
        link(a, b, fwd[k], back[k]);
      } else {
        link(a, mid, fwd[k], back[k]);
        link(mid, b, fwd[k], back[k]);
        g.tjunctions.push_back({mid, qi, k});
        g.neighbors[mid][inward[k]] = {Neighbor::Kind::quad_centroid, qi};
      }
    }
  }
  return g;
}

}  // namespace

std::uint32_t Grid::quad_at(XY p) const {
  int width = cols << max_level, height = rows << max_level;
  double unit = cell / (1 << max_level);
  int x = std::clamp(static_cast<int>(std::floor((p.x - origin.x) / unit)), 0, width - 1);
  int y = std::clamp(static_cast<int>(std::floor((p.y - origin.y) / unit)), 0, height - 1);
  return cell_quad[static_cast<std::size_t>(y) * width + x];
}

Frame frame_around(const std::vector<XY>& points, int cells, double margin) {
  if (cells < 1) throw std::invalid_argument("grid needs at least one cell");
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
  if (!points.empty()) {
    x0 = x1 = points[0].x;
    y0 = y1 = points[0].y;
    for (const auto& p : points) {
      x0 = std::min(x0, p.x);
      x1 = std::max(x1, p.x);
      y0 = std::min(y0, p.y);
      y1 = std::max(y1, p.y);
    }
  }
  double span = std::max({x1 - x0, y1 - y0, 1e-9});
  double pad = span * margin;
  Frame f;
  f.cell = (span + 2 * pad) / cells;
  f.cols = std::max(1, static_cast<int>(std::ceil((x1 - x0 + 2 * pad) / f.cell - 1e-9)));
  f.rows = std::max(1, static_cast<int>(std::ceil((y1 - y0 + 2 * pad) / f.cell - 1e-9)));
  // Centre the map in the frame.
  f.origin = {(x0 + x1) / 2 - f.cols * f.cell / 2, (y0 + y1) / 2 - f.rows * f.cell / 2};
  return f;
}

Grid build_uniform(const Frame& frame) { return build_adaptive(frame, {}, {}, {frame.cols, 0, 0}); }

Grid build_adaptive(const Frame& frame, const std::vector<XY>& points, const std::vector<XY>& special,
                    const AdaptiveParams& params) {
  if (params.max_depth < 0 || params.max_depth > 12) throw std::invalid_argument("max_depth out of range");
  Lattice lat{params.max_depth, frame.cols << params.max_depth, frame.rows << params.max_depth, frame.origin,
              frame.cell / (1 << params.max_depth)};
  CellCounts counts(lat.width, lat.height), specials(lat.width, lat.height);
  for (const auto& p : points) {
    auto [x, y] = lat.cell_of(p);
    counts.add(x, y);
  }
  for (const auto& p : special) {
    auto [x, y] = lat.cell_of(p);
    specials.add(x, y);
  }
  counts.finish();
  specials.finish();

  LeafLevels levels(lat);
  // Depth-first refinement of every base cell.
  struct Pending {
    int x, y, level;
  };
  std::vector<Pending> stack;
  for (int by = 0; by < frame.rows; ++by)
    for (int bx = 0; bx < frame.cols; ++bx) stack.push_back({bx << lat.depth, by << lat.depth, 0});
  while (!stack.empty()) {
    auto q = stack.back();
    stack.pop_back();
    int s = lat.cells_per_side(q.level);
    bool split = q.level < lat.depth &&
                 (counts.count(q.x, q.y, q.x + s, q.y + s) > params.max_vertices ||
                  specials.count(q.x, q.y, q.x + s, q.y + s) > 0);
    if (!split) {
      levels.set(q.x, q.y, s, q.level);
      continue;
    }
    int h = s / 2;
    for (auto [dx, dy] : {std::pair{0, 0}, std::pair{h, 0}, std::pair{0, h}, std::pair{h, h}})
      stack.push_back({q.x + dx, q.y + dy, q.level + 1});
  }
  balance(levels, lat);
  return assemble(frame, lat, levels);
}

std::size_t count_grid_edges(const Grid& grid) {
  std::size_t n = 0;
  for (const auto& nb : grid.neighbors)
    n += (nb[kRight].kind == Neighbor::Kind::vertex) + (nb[kUp].kind == Neighbor::Kind::vertex);
  return n;
}

}  // namespace tourmap::grid
