#include "deform/foldover.hpp"

#include "util/stop.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <set>

namespace tourmap::deform {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;

bool quad_ok(const std::array<XY, 4>& c) {
  for (int k = 0; k < 4; ++k) {
    const auto& a = c[(k + 3) % 4];
    const auto& b = c[k];
    const auto& d = c[(k + 1) % 4];
    if (CGAL::orientation(Point(a.x, a.y), Point(b.x, b.y), Point(d.x, d.y)) != CGAL::LEFT_TURN) return false;
  }
  return true;
}

std::vector<std::uint32_t> folded_quads(const grid::Grid& g, const std::vector<XY>& pos) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t q = 0; q < g.quads.size(); ++q)
    if (!quad_ok(grid::corners_of(g, pos, q))) out.push_back(q);
  return out;
}

// Every pair of edges without a shared node whose segments at `nodes` meet, handed to
// f(a0, a1, b0, b1) (CGAL box intersection + exact segment predicates).
template <class F>
void for_each_crossing(const std::vector<XY>& nodes, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges,
                       F&& f) {
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 2, std::size_t, CGAL::Box_intersection_d::ID_EXPLICIT>;
  std::vector<Box> boxes;
  boxes.reserve(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto& a = nodes[edges[i].first];
    const auto& b = nodes[edges[i].second];
    double lo[2] = {std::min(a.x, b.x), std::min(a.y, b.y)}, hi[2] = {std::max(a.x, b.x), std::max(a.y, b.y)};
    boxes.emplace_back(lo, hi, i);
  }
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    const auto [a0, a1] = edges[x.handle()];
    const auto [b0, b1] = edges[y.handle()];
    if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1) return;  // adjacent edges meet at their node
    Kernel::Segment_2 s(Point(nodes[a0].x, nodes[a0].y), Point(nodes[a1].x, nodes[a1].y));
    Kernel::Segment_2 t(Point(nodes[b0].x, nodes[b0].y), Point(nodes[b1].x, nodes[b1].y));
    if (CGAL::do_intersect(s, t)) f(a0, a1, b0, b1);
  });
}

}  // namespace

std::size_t count_inverted_quads(const grid::Grid& g, const std::vector<XY>& pos) { return folded_quads(g, pos).size(); }

std::size_t count_crossings(const std::vector<XY>& nodes,
                            const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges) {
  std::size_t crossings = 0;
  for_each_crossing(nodes, edges, [&](std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t) { ++crossings; });
  return crossings;
}

double touching_distance(const PlanarNetwork& net) {
  constexpr double kTouchingMetres = 2.0;  // less than a lane: the two roads' surfaces overlap
  return kTouchingMetres / (net.transform.metres_per_unit > 0 ? net.transform.metres_per_unit : 1.0);
}

double segment_distance(XY a, XY b, XY c, XY d) {
  if (CGAL::do_intersect(Kernel::Segment_2({a.x, a.y}, {b.x, b.y}), Kernel::Segment_2({c.x, c.y}, {d.x, d.y}))) return 0;
  auto to = [](XY p, XY s, XY t) {
    const double dx = t.x - s.x, dy = t.y - s.y, len2 = dx * dx + dy * dy;
    const double u = len2 > 0 ? std::clamp(((p.x - s.x) * dx + (p.y - s.y) * dy) / len2, 0.0, 1.0) : 0.0;
    return std::hypot(p.x - s.x - u * dx, p.y - s.y - u * dy);
  };
  return std::min({to(a, c, d), to(b, c, d), to(c, a, b), to(d, a, b)});
}

std::size_t count_added_crossings(const PlanarNetwork& net, const std::vector<XY>& nodes) {
  const double touching = touching_distance(net);
  std::size_t added = 0;
  for_each_crossing(nodes, net.edges, [&](std::uint32_t a0, std::uint32_t a1, std::uint32_t b0, std::uint32_t b1) {
    if (segment_distance(net.nodes[a0], net.nodes[a1], net.nodes[b0], net.nodes[b1]) > touching) ++added;
  });
  return added;
}

void snap_tjunctions(const grid::Grid& g, std::vector<XY>& pos) {
  // Restricted quadtree (2:1 across sides): a coarse side holds at most one T-junction, and no
  // coarse quad's corner is itself a T-junction of a side that holds one (its finer neighbour
  // would be two levels finer than the quad beyond), so the order does not matter.
  for (const auto& t : g.tjunctions) {
    const auto& c = g.quads[t.coarse_quad].corners;
    const XY a = pos[c[t.side]], b = pos[c[(t.side + 1) % 4]];
    pos[t.vertex] = {0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
  }
}

void smooth_vertices(const Prepared& p, std::vector<XY>& points, const std::vector<std::uint32_t>& vertices) {
  const auto& g = *p.grid;
  std::vector<std::pair<std::uint32_t, XY>> next;
  next.reserve(vertices.size());
  for (auto v : vertices) {
    // The neighbours' average, now and at rest: the target keeps v's rest offset from it
    // (the displacement's Laplacian goes to zero, eq. 4.4's smoothness).
    XY sum{0, 0}, rest_sum{0, 0};
    int n = 0;
    for (const auto& nb : g.neighbors[v]) {
      if (nb.kind == grid::Neighbor::Kind::vertex) {
        sum.x += points[nb.index].x, sum.y += points[nb.index].y;
        rest_sum.x += p.rest[nb.index].x, rest_sum.y += p.rest[nb.index].y;
        ++n;
      } else if (nb.kind == grid::Neighbor::Kind::quad_centroid) {
        for (auto c : g.quads[nb.index].corners) {
          sum.x += 0.25 * points[c].x, sum.y += 0.25 * points[c].y;
          rest_sum.x += 0.25 * p.rest[c].x, rest_sum.y += 0.25 * p.rest[c].y;
        }
        ++n;
      }
    }
    if (n == 0) continue;
    XY target{sum.x / n + p.rest[v].x - rest_sum.x / n, sum.y / n + p.rest[v].y - rest_sum.y / n};
    XY moved = points[v];
    if (p.column[v][0] >= 0) moved.x = 0.5 * (moved.x + target.x);
    if (p.column[v][1] >= 0) moved.y = 0.5 * (moved.y + target.y);
    next.emplace_back(v, moved);
  }
  for (const auto& [v, pos] : next) points[v] = pos;
  snap_tjunctions(g, points);
}

int relax_foldovers(const Prepared& p, std::vector<XY>& points, int max_iterations,
                    std::chrono::steady_clock::time_point until) {
  if (p.method != Method::grid || !p.grid) return 0;
  const auto& g = *p.grid;
  int it = 0;
  for (; it < max_iterations && std::chrono::steady_clock::now() < until; ++it) {
    util::check_stop();
    auto folded = folded_quads(g, points);
    if (folded.empty()) break;
    std::set<std::uint32_t> moving;
    for (auto q : folded)
      for (auto v : g.quads[q].corners) moving.insert(v);
    smooth_vertices(p, points, {moving.begin(), moving.end()});
  }
  return it;
}

}  // namespace tourmap::deform
