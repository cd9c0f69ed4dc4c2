#include "metro/topology_guard.hpp"

#include <algorithm>
#include <cmath>

namespace tourmap::metro {
namespace {

double orient(XY a, XY b, XY c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

bool on_segment(XY a, XY b, XY p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}

std::uint32_t other_end(const LayoutGraph& g, std::uint32_t e, std::uint32_t v) {
  return g.edges[e].first == v ? g.edges[e].second : g.edges[e].first;
}

bool shares_node(const LayoutGraph& g, std::uint32_t e, std::uint32_t f) {
  auto [a, b] = g.edges[e];
  auto [c, d] = g.edges[f];
  return a == c || a == d || b == c || b == d;
}

// Neighbours of v counter-clockwise around `at`, with node `moved` taken at `moved_to`,
// starting from the smallest node id (so equal cycles compare equal).
std::vector<std::uint32_t> circular_order(const TopologyGuard& guard, const LayoutGraph& g, const std::vector<XY>& pos,
                                          std::uint32_t v, XY at, std::uint32_t moved, XY moved_to) {
  std::vector<std::pair<double, std::uint32_t>> around;
  for (auto e : guard.incident[v]) {
    auto w = other_end(g, e, v);
    XY p = w == moved ? moved_to : pos[w];
    around.push_back({std::atan2(p.y - at.y, p.x - at.x), w});
  }
  std::sort(around.begin(), around.end());
  std::vector<std::uint32_t> out;
  for (const auto& [angle, w] : around) out.push_back(w);
  auto first = std::min_element(out.begin(), out.end());
  std::rotate(out.begin(), first, out.end());
  return out;
}

bool strictly_inside(XY a, XY b, XY c, XY p) {
  double o1 = orient(a, b, p), o2 = orient(b, c, p), o3 = orient(c, a, p);
  return (o1 > 0 && o2 > 0 && o3 > 0) || (o1 < 0 && o2 < 0 && o3 < 0);
}

}  // namespace

bool segments_intersect(XY a, XY b, XY c, XY d) {
  double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) || (o3 == 0 && on_segment(c, d, a)) ||
         (o4 == 0 && on_segment(c, d, b));
}

TopologyGuard make_topology_guard(const LayoutGraph& g, const std::vector<XY>& start) {
  TopologyGuard guard;
  const std::size_t n = start.size(), m = g.edges.size();
  guard.incident.resize(n);
  for (std::uint32_t e = 0; e < m; ++e) {
    guard.incident[g.edges[e].first].push_back(e);
    guard.incident[g.edges[e].second].push_back(e);
  }
  guard.crossing.resize(m);
  for (std::uint32_t e = 0; e < m; ++e)
    for (std::uint32_t f = e + 1; f < m; ++f) {
      if (shares_node(g, e, f)) continue;
      if (segments_intersect(start[g.edges[e].first], start[g.edges[e].second], start[g.edges[f].first], start[g.edges[f].second])) {
        guard.crossing[e].push_back(f);
        guard.crossing[f].push_back(e);
      }
    }
  for (auto& list : guard.crossing) std::sort(list.begin(), list.end());
  guard.order.resize(n);
  for (std::uint32_t v = 0; v < n; ++v) guard.order[v] = circular_order(guard, g, start, v, start[v], v, start[v]);
  return guard;
}

bool move_keeps_topology(const TopologyGuard& guard, const LayoutGraph& g, const std::vector<XY>& pos, std::uint32_t node,
                         XY to) {
  const XY from = pos[node];
  // Crossings of the node's edges: exactly the expected ones (segments whose bounding boxes
  // are apart cannot cross: the cheap test first, this runs for every node and iteration).
  for (auto e : guard.incident[node]) {
    const XY far = pos[other_end(g, e, node)];
    const double x0 = std::min(to.x, far.x), x1 = std::max(to.x, far.x), y0 = std::min(to.y, far.y), y1 = std::max(to.y, far.y);
    const auto& expected = guard.crossing[e];
    std::size_t found = 0;
    for (std::uint32_t f = 0; f < g.edges.size(); ++f) {
      const XY c = pos[g.edges[f].first], d = pos[g.edges[f].second];
      if (std::max(c.x, d.x) < x0 || std::min(c.x, d.x) > x1 || std::max(c.y, d.y) < y0 || std::min(c.y, d.y) > y1) continue;
      if (f == e || shares_node(g, e, f) || !segments_intersect(to, far, c, d)) continue;
      if (!std::binary_search(expected.begin(), expected.end(), f)) return false;
      ++found;
    }
    if (found != expected.size()) return false;
  }
  // No node swept over by an edge (nor hit by the node itself).
  for (auto e : guard.incident[node]) {
    const auto far_node = other_end(g, e, node);
    const XY far = pos[far_node];
    const double x0 = std::min({from.x, to.x, far.x}), x1 = std::max({from.x, to.x, far.x});
    const double y0 = std::min({from.y, to.y, far.y}), y1 = std::max({from.y, to.y, far.y});
    for (std::uint32_t k = 0; k < pos.size(); ++k) {
      const XY p = pos[k];
      if (p.x < x0 || p.x > x1 || p.y < y0 || p.y > y1) continue;
      if (k != node && k != far_node && strictly_inside(from, to, far, p)) return false;
    }
  }
  for (std::uint32_t k = 0; k < pos.size(); ++k)
    if (k != node && pos[k].x == to.x && pos[k].y == to.y) return false;
  // Circular orders at the node and its neighbours (only nodes with 3+ edges have one to lose).
  if (guard.incident[node].size() >= 3 && circular_order(guard, g, pos, node, to, node, to) != guard.order[node]) return false;
  for (auto e : guard.incident[node]) {
    auto w = other_end(g, e, node);
    if (guard.incident[w].size() >= 3 && circular_order(guard, g, pos, w, pos[w], node, to) != guard.order[w]) return false;
  }
  return true;
}

}  // namespace tourmap::metro
