#include "metro/station_gap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace tourmap::metro {
namespace {

double point_segment(XY p, XY a, XY b) {
  double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

struct Segment {
  std::uint32_t edge;
  XY a, b;
};

// Uniform grid of cell size `h`: every node, and every path segment in the cells of its
// pieces of length <= h (a piece touches at most 2 x 2 cells, however it is oriented; the
// segment's bounding box could cover many more).
class Grid {
 public:
  Grid(double h, XY origin) : h_(h), origin_(origin) {}
  std::int64_t cell(double v, double o) const { return static_cast<std::int64_t>(std::floor((v - o) / h_)); }
  static std::uint64_t key(std::int64_t cx, std::int64_t cy) {
    return (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint32_t>(cy);
  }
  void add(XY lo, XY hi, std::uint32_t item, bool segment) {
    for (auto cx = cell(lo.x, origin_.x); cx <= cell(hi.x, origin_.x); ++cx)
      for (auto cy = cell(lo.y, origin_.y); cy <= cell(hi.y, origin_.y); ++cy) {
        auto& items = (segment ? segments_ : nodes_)[key(cx, cy)];
        if (items.empty() || items.back() != item) items.push_back(item);
      }
  }
  // Items in the 3 x 3 cells around p: all those within h of p, and maybe more (a segment
  // possibly more than once).
  template <typename F>
  void near(XY p, bool segment, F&& f) const {
    const auto& map = segment ? segments_ : nodes_;
    auto cx = cell(p.x, origin_.x), cy = cell(p.y, origin_.y);
    for (auto x = cx - 1; x <= cx + 1; ++x)
      for (auto y = cy - 1; y <= cy + 1; ++y)
        if (auto it = map.find(key(x, y)); it != map.end())
          for (auto item : it->second) f(item);
  }

 private:
  double h_;
  XY origin_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> nodes_, segments_;
};

// The smallest gap if it is at most h, else something larger than h.
double gap_within(const LayoutGraph& g, const Layout& L, const std::vector<std::vector<std::uint32_t>>& adjacent,
                  double h, XY origin) {
  Grid grid(h, origin);
  for (std::uint32_t v = 0; v < L.pos.size(); ++v) grid.add(L.pos[v], L.pos[v], v, false);
  std::vector<Segment> segments;
  for (std::uint32_t e = 0; e < L.paths.size(); ++e)
    for (std::size_t i = 1; i < L.paths[e].size(); ++i) {
      XY a = L.paths[e][i - 1], b = L.paths[e][i];
      auto id = static_cast<std::uint32_t>(segments.size());
      segments.push_back({e, a, b});
      auto n = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(std::hypot(b.x - a.x, b.y - a.y) / h)));
      for (std::size_t k = 0; k < n; ++k) {
        XY p{a.x + (b.x - a.x) * k / n, a.y + (b.y - a.y) * k / n};
        XY q = k + 1 == n ? b : XY{a.x + (b.x - a.x) * (k + 1) / n, a.y + (b.y - a.y) * (k + 1) / n};
        grid.add({std::min(p.x, q.x), std::min(p.y, q.y)}, {std::max(p.x, q.x), std::max(p.y, q.y)}, id, true);
      }
    }
  double best = std::numeric_limits<double>::infinity();
  for (std::uint32_t v = 0; v < L.pos.size(); ++v) {
    const XY p = L.pos[v];
    grid.near(p, false, [&](std::uint32_t w) {
      if (w == v || std::binary_search(adjacent[v].begin(), adjacent[v].end(), w)) return;
      best = std::min(best, std::hypot(L.pos[w].x - p.x, L.pos[w].y - p.y));
    });
    grid.near(p, true, [&](std::uint32_t i) {
      const auto& s = segments[i];
      if (g.edges[s.edge].first == v || g.edges[s.edge].second == v) return;
      best = std::min(best, point_segment(p, s.a, s.b));
    });
  }
  return best;
}

}  // namespace

double min_station_gap(const LayoutGraph& g, const Layout& L) {
  const std::size_t n = L.pos.size();
  std::vector<std::vector<std::uint32_t>> adjacent(n);
  for (auto [u, v] : g.edges) {
    adjacent[u].push_back(v);
    adjacent[v].push_back(u);
  }
  for (auto& a : adjacent) std::sort(a.begin(), a.end());
  XY lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  XY hi{-lo.x, -lo.y};
  double length = 0;
  std::size_t segments = 0;
  auto extend = [&](XY p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  };
  for (const auto& p : L.pos) extend(p);
  for (const auto& path : L.paths)
    for (std::size_t i = 0; i < path.size(); ++i) {
      extend(path[i]);
      if (i == 0) continue;
      length += std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
      ++segments;
    }
  if (n < 2) return std::numeric_limits<double>::infinity();
  const double span = std::max(hi.x - lo.x, hi.y - lo.y);
  // Start at the mean segment length: the gap is usually a fraction of an edge. A gap found
  // within the cell size is exact (every closer item lies in the 3 x 3 cells around a node);
  // otherwise the cells grow until they hold the whole layout.
  double h = segments && length > 0 ? length / segments : span;
  if (!(h > 0)) h = 1;  // everything at one point: one cell holds it all
  for (;;) {
    double best = gap_within(g, L, adjacent, h, lo);
    if (best <= h || h >= span) return best;
    h = std::min(4 * h, span);
  }
}

}  // namespace tourmap::metro
