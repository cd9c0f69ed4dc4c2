#include "metro/layout_quality.hpp"

#include "metro/station_gap.hpp"
#include "metro/warp.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <set>

namespace tourmap::metro {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

bool octilinear(XY a, XY b) {
  double q = std::atan2(b.y - a.y, b.x - a.x) / (M_PI / 4);
  return std::abs(q - std::round(q)) < 1e-6;
}

double angle(XY from, XY to) { return std::atan2(to.y - from.y, to.x - from.x); }

// The path of edge e as seen from node v: from v outwards.
XY first_step(const LayoutGraph& g, const Layout& L, std::uint32_t e, std::uint32_t v) {
  const auto& p = L.paths[e];
  return g.edges[e].first == v ? p[1] : p[p.size() - 2];
}

bool same_cycle(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  if (a.size() != b.size()) return false;
  auto it = std::find(b.begin(), b.end(), a.front());
  if (it == b.end()) return false;
  std::size_t off = static_cast<std::size_t>(it - b.begin());
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[(i + off) % b.size()]) return false;
  return true;
}

}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> crossing_path_pairs(
    const std::vector<std::vector<XY>>& paths, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges) {
  struct Segment {
    std::size_t edge;
    XY a, b;
  };
  std::vector<Segment> segs;
  for (std::size_t e = 0; e < paths.size(); ++e)
    for (std::size_t i = 1; i < paths[e].size(); ++i) segs.push_back({e, paths[e][i - 1], paths[e][i]});
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 2, std::size_t, CGAL::Box_intersection_d::ID_EXPLICIT>;
  std::vector<Box> boxes;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const auto& s = segs[i];
    double lo[2] = {std::min(s.a.x, s.b.x), std::min(s.a.y, s.b.y)}, hi[2] = {std::max(s.a.x, s.b.x), std::max(s.a.y, s.b.y)};
    boxes.emplace_back(lo, hi, i);
  }
  std::set<std::pair<std::size_t, std::size_t>> crossing;
  auto check = [&](const Box& x, const Box& y) {
    const auto& s = segs[x.handle()];
    const auto& t = segs[y.handle()];
    if (s.edge == t.edge) return;
    auto key = std::minmax(s.edge, t.edge);
    if (crossing.count(key)) return;
    // Edges that share a node meet there: their segments at that node cross only by
    // overlapping (collinear, same side). Decided by exact predicates, as the computed
    // meeting point of nearly collinear segments can be far off.
    auto [e0, e1] = edges[s.edge];
    auto [f0, f1] = edges[t.edge];
    if (e0 == f0 || e0 == f1 || e1 == f0 || e1 == f1) {
      const auto& ps = paths[s.edge];
      const auto& pt = paths[t.edge];
      auto same = [](XY a, XY b) {  // equal up to rounding
        const double tolerance = 1e-9 * std::max({1.0, std::abs(a.x), std::abs(a.y)});
        return std::abs(a.x - b.x) <= tolerance && std::abs(a.y - b.y) <= tolerance;
      };
      for (XY shared : {ps.front(), ps.back()}) {
        if (!same(shared, pt.front()) && !same(shared, pt.back())) continue;
        const XY* a = same(s.a, shared) ? &s.b : same(s.b, shared) ? &s.a : nullptr;
        const XY* b = same(t.a, shared) ? &t.b : same(t.b, shared) ? &t.a : nullptr;
        if (!a || !b) continue;  // not both segments at the shared node
        const bool overlap = CGAL::orientation(Kernel::Point_2(shared.x, shared.y), Kernel::Point_2(a->x, a->y),
                                               Kernel::Point_2(b->x, b->y)) == CGAL::COLLINEAR &&
                             (a->x - shared.x) * (b->x - shared.x) + (a->y - shared.y) * (b->y - shared.y) > 0;
        if (overlap) crossing.insert(key);
        return;
      }
    }
    if (!CGAL::do_intersect(Kernel::Segment_2({s.a.x, s.a.y}, {s.b.x, s.b.y}), Kernel::Segment_2({t.a.x, t.a.y}, {t.b.x, t.b.y})))
      return;
    crossing.insert(key);
  };
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), check);
  return {crossing.begin(), crossing.end()};
}

std::size_t count_path_crossings(const std::vector<std::vector<XY>>& paths,
                                 const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges) {
  return crossing_path_pairs(paths, edges).size();
}

std::size_t count_order_violations(const LayoutGraph& g, const Layout& L) {
  const std::size_t n = g.pos.size();
  std::vector<std::vector<std::uint32_t>> incident(n);
  for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
    incident[g.edges[e].first].push_back(e);
    incident[g.edges[e].second].push_back(e);
  }
  auto geo_other = [&](std::uint32_t e, std::uint32_t v) { return g.pos[g.edges[e].first == v ? g.edges[e].second : g.edges[e].first]; };
  std::size_t violations = 0;
  for (std::uint32_t v = 0; v < n; ++v) {
    const auto& inc = incident[v];
    if (inc.size() < 3) continue;
    std::vector<std::uint32_t> geo = inc, lay = inc;
    std::sort(geo.begin(), geo.end(), [&](auto x, auto y) {
      return angle(g.pos[v], geo_other(x, v)) < angle(g.pos[v], geo_other(y, v));
    });
    std::sort(lay.begin(), lay.end(), [&](auto x, auto y) {
      return angle(L.pos[v], first_step(g, L, x, v)) < angle(L.pos[v], first_step(g, L, y, v));
    });
    bool distinct = true;
    for (std::size_t i = 1; i < lay.size(); ++i)
      distinct = distinct && std::abs(angle(L.pos[v], first_step(g, L, lay[i], v)) -
                                      angle(L.pos[v], first_step(g, L, lay[i - 1], v))) > 1e-9;
    if (!distinct || !same_cycle(geo, lay)) ++violations;
  }
  return violations;
}

LayoutQuality measure_layout(const LayoutGraph& g, const Layout& L) {
  LayoutQuality q;
  std::size_t n = g.pos.size(), m = g.edges.size();
  if (m == 0) return q;
  std::size_t oct = 0;
  q.min_edge = std::numeric_limits<double>::infinity();
  for (std::size_t e = 0; e < m; ++e) {
    const auto& p = L.paths[e];
    bool all = true;
    double len = 0;
    for (std::size_t i = 1; i < p.size(); ++i) {
      all = all && octilinear(p[i - 1], p[i]);
      len += std::hypot(p[i].x - p[i - 1].x, p[i].y - p[i - 1].y);
      if (i >= 2 && std::abs(angle(p[i - 2], p[i - 1]) - angle(p[i - 1], p[i])) > 1e-6) ++q.bends;
    }
    oct += all;
    q.min_edge = std::min(q.min_edge, len);
    q.mean_edge += len / m;
  }
  q.octilinear_share = static_cast<double>(oct) / m;

  std::vector<std::vector<std::uint32_t>> incident(n);
  for (std::uint32_t e = 0; e < m; ++e) {
    incident[g.edges[e].first].push_back(e);
    incident[g.edges[e].second].push_back(e);
  }
  for (std::uint32_t v = 0; v < n; ++v) {
    const auto& inc = incident[v];
    // Bends along lines through the station: a line on exactly two of its edges should pass straight.
    std::map<std::uint32_t, std::vector<std::uint32_t>> by_line;
    for (auto e : inc)
      for (auto l : g.edge_lines[e]) by_line[l].push_back(e);
    if (by_line.empty() && inc.size() == 2) by_line[0] = inc;
    for (const auto& [line, es] : by_line) {
      if (es.size() != 2) continue;
      double a = angle(L.pos[v], first_step(g, L, es[0], v)), b = angle(L.pos[v], first_step(g, L, es[1], v));
      double diff = std::fmod(std::abs(a - b), 2 * M_PI);
      if (std::abs(diff - M_PI) > 1e-6) ++q.bends;
    }
  }
  q.order_violations = count_order_violations(g, L);

  auto crossing = crossing_path_pairs(L.paths, g.edges);
  std::vector<std::vector<XY>> straight;
  for (auto [u, v] : g.edges) straight.push_back({g.pos[u], g.pos[v]});
  auto geo_crossing = crossing_path_pairs(straight, g.edges);  // both sorted
  q.crossings = crossing.size();
  q.geo_crossings = geo_crossing.size();
  std::vector<std::pair<std::size_t, std::size_t>> added;
  std::set_difference(crossing.begin(), crossing.end(), geo_crossing.begin(), geo_crossing.end(), std::back_inserter(added));
  q.added_crossings = added.size();

  auto h = fit_helmert(g.pos, L.pos);
  double sum = 0;
  for (std::size_t v = 0; v < n; ++v) {
    auto p = h.apply(g.pos[v]);
    sum += std::hypot(p.x - L.pos[v].x, p.y - L.pos[v].y);
  }
  q.mean_displacement = n && q.mean_edge > 0 ? sum / n / q.mean_edge : 0;
  q.min_station_gap = min_station_gap(g, L);
  q.min_station_gap_ratio = q.mean_edge > 0 ? q.min_station_gap / q.mean_edge : 0;
  return q;
}

}  // namespace tourmap::metro
