#include "deform/untangle.hpp"

#include "deform/foldover.hpp"
#include "util/stop.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace tourmap::deform {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 2, std::size_t, CGAL::Box_intersection_d::ID_EXPLICIT>;

constexpr std::uint32_t kMaxSamples = 16;
// Two roads d apart at rest stay about sigma * d apart deformed, sigma the smallest singular
// value of the grid's Jacobian around them, so their chords can only cross when one strays
// from its road by about half of that; an edge is examined from a quarter of it on (a margin
// for sigma varying between the two). A bound, not a proof: count_added_crossings is exact.
constexpr double kStrayShare = 0.25;
// Clearance is searched this share of the quad around an edge's middle far (further costs the
// search more than it saves: an edge past it is examined a little early).
constexpr double kReachShare = 0.125;
// The smoothed area grows by one ring of vertices every this many steps without success.
constexpr int kStepsPerRing = 4;

double point_segment_distance2(XY p, XY a, XY b) {
  const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  const double ex = p.x - a.x - t * dx, ey = p.y - a.y - t * dy;
  return ex * ex + ey * ey;
}

// CSR from (key, value) pairs.
void to_csr(std::size_t keys, std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
            std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& values) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  start.assign(keys + 1, 0);
  for (const auto& [k, v] : pairs) ++start[k + 1];
  for (std::size_t k = 0; k < keys; ++k) start[k + 1] += start[k];
  values.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) values[i] = pairs[i].second;
}

// The smallest singular value of the bilinear map's Jacobian at the quad's four corners
// (rest quads are squares of side `size`).
double min_stretch(const std::array<XY, 4>& c, double size) {
  double lowest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 4; ++k) {
    // At corner k the parameter axes run to the next and the previous corner (u then v, or v then u).
    const XY o = c[k], p = c[(k + 1) % 4], q = c[(k + 3) % 4];
    const double a = (p.x - o.x) / size, b = (q.x - o.x) / size, cc = (p.y - o.y) / size, d = (q.y - o.y) / size;
    const double t = a * a + b * b + cc * cc + d * d, det = a * d - b * cc;
    lowest = std::min(lowest, std::sqrt(std::max(0.0, (t - std::sqrt(std::max(0.0, t * t - 4 * det * det))) / 2)));
  }
  return lowest;
}

bool segments_cross(XY a, XY b, XY c, XY d) {
  return CGAL::do_intersect(Kernel::Segment_2({a.x, a.y}, {b.x, b.y}), Kernel::Segment_2({c.x, c.y}, {d.x, d.y}));
}

// Every quad an edge's endpoints and samples lie in, handed to `f`.
template <class F>
void for_each_quad(const Prepared& p, const PlanarNetwork& net, std::size_t e, F&& f) {
  f(p.embeddings[net.edges[e].first].quad);
  f(p.embeddings[net.edges[e].second].quad);
  const auto& s = p.edge_samples;
  for (auto i = s.start[e]; i < s.start[e + 1]; ++i) f(s.samples[i].quad);
}

}  // namespace

EdgeSamples sample_edges(const grid::Grid& g, const PlanarNetwork& net) {
  EdgeSamples out;
  out.start.reserve(net.edges.size() + 1);
  for (const auto& [a, b] : net.edges) {
    out.start.push_back(static_cast<std::uint32_t>(out.samples.size()));
    const XY pa = net.nodes[a], pb = net.nodes[b];
    const double len = std::hypot(pb.x - pa.x, pb.y - pa.y);
    const double spacing = 0.5 * std::min(g.quads[g.quad_at(pa)].size, g.quads[g.quad_at(pb)].size);
    const auto pieces = static_cast<std::uint32_t>(
        std::clamp(std::ceil(spacing > 0 ? len / spacing : 2.0), 2.0, static_cast<double>(kMaxSamples + 1)));
    for (std::uint32_t i = 1; i < pieces; ++i) {
      const double t = static_cast<double>(i) / pieces;
      out.samples.push_back(grid::embed(g, {pa.x + t * (pb.x - pa.x), pa.y + t * (pb.y - pa.y)}));
    }
  }
  out.start.push_back(static_cast<std::uint32_t>(out.samples.size()));
  // Clearance: the rest distance to the nearest road that neither shares a node nor touches
  // (or crosses) this one, searched within kReachShare of the quad under the edge's middle.
  const double touching = touching_distance(net);
  std::vector<Box> boxes;
  boxes.reserve(net.edges.size());
  out.clearance.resize(net.edges.size());
  for (std::size_t e = 0; e < net.edges.size(); ++e) {
    const XY a = net.nodes[net.edges[e].first], b = net.nodes[net.edges[e].second];
    const double reach = kReachShare * g.quads[g.quad_at({(a.x + b.x) / 2, (a.y + b.y) / 2})].size;
    out.clearance[e] = static_cast<float>(reach);
    double lo[2] = {std::min(a.x, b.x) - reach, std::min(a.y, b.y) - reach};
    double hi[2] = {std::max(a.x, b.x) + reach, std::max(a.y, b.y) + reach};
    boxes.emplace_back(lo, hi, e);
  }
  // Incidence: which edges lie in each quad, which quads meet at each vertex.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> incidence;
  for (std::uint32_t e = 0; e < net.edges.size(); ++e) {
    incidence.emplace_back(g.quad_at(net.nodes[net.edges[e].first]), e);
    incidence.emplace_back(g.quad_at(net.nodes[net.edges[e].second]), e);
    for (auto i = out.start[e]; i < out.start[e + 1]; ++i) incidence.emplace_back(out.samples[i].quad, e);
  }
  to_csr(g.quads.size(), incidence, out.quad_edges_start, out.quad_edges);
  incidence.clear();
  for (std::uint32_t q = 0; q < g.quads.size(); ++q)
    for (auto v : g.quads[q].corners) incidence.emplace_back(v, q);
  to_csr(g.vertices.size(), incidence, out.vertex_quads_start, out.vertex_quads);
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    const auto e = x.handle(), f = y.handle();
    const auto [a0, a1] = net.edges[e];
    const auto [b0, b1] = net.edges[f];
    if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1) return;
    const double d = segment_distance(net.nodes[a0], net.nodes[a1], net.nodes[b0], net.nodes[b1]);
    if (d <= touching) return;
    out.clearance[e] = std::min(out.clearance[e], static_cast<float>(d));
    out.clearance[f] = std::min(out.clearance[f], static_cast<float>(d));
  });
  return out;
}

UntangleReport untangle_crossings(const Prepared& p, const PlanarNetwork& net, std::vector<XY>& points,
                                  std::vector<XY>& nodes, int max_steps, std::chrono::steady_clock::time_point until) {
  UntangleReport report;
  const auto& s = p.edge_samples;
  if (p.method != Method::grid || !p.grid || s.start.size() != net.edges.size() + 1) return report;
  const auto& g = *p.grid;
  const std::size_t edges = net.edges.size();
  const double touching = touching_distance(net);
  const double noise = 1e-9 * std::max({net.max.x - net.min.x, net.max.y - net.min.y, 1e-12});  // rounding, not straying
  nodes = road_nodes_from(p, points);

  // Marks with a generation stamp, so that a step clears nothing.
  std::uint32_t stamp = 0;
  std::vector<std::uint32_t> quad_mark(g.quads.size(), 0), edge_mark(edges, 0), listed(edges, 0),
      vertex_mark(g.vertices.size(), 0);
  std::vector<char> suspect(edges, 0), affected(edges, 1);
  // Each quad's least stretch, measured when first needed (NaN: not yet, or its corners moved).
  std::vector<double> stretch(g.quads.size(), std::numeric_limits<double>::quiet_NaN());
  auto stretch_of = [&](std::uint32_t q) {
    if (std::isnan(stretch[q])) stretch[q] = min_stretch(grid::corners_of(g, points, q), g.quads[q].size);
    return stretch[q];
  };
  auto quads_at = [&](std::uint32_t v, auto&& f) {
    for (auto i = s.vertex_quads_start[v]; i < s.vertex_quads_start[v + 1]; ++i) f(s.vertex_quads[i]);
  };
  auto edges_in = [&](std::uint32_t q, auto&& f) {
    for (auto i = s.quad_edges_start[q]; i < s.quad_edges_start[q + 1]; ++i) f(s.quad_edges[i]);
  };
  // Quads `list` and those sharing a corner with them, marked with a new stamp; returns that stamp.
  auto mark_with_ring = [&](const std::vector<std::uint32_t>& list) {
    const auto mark = ++stamp;
    for (auto q : list)
      for (auto v : g.quads[q].corners)
        quads_at(v, [&](std::uint32_t r) { quad_mark[r] = mark; });
    return mark;
  };
  auto box_of = [&](std::size_t e) {
    const XY a = nodes[net.edges[e].first], b = nodes[net.edges[e].second];
    double lo[2] = {std::min(a.x, b.x), std::min(a.y, b.y)}, hi[2] = {std::max(a.x, b.x), std::max(a.y, b.y)};
    return Box(lo, hi, e);
  };
  // Does edge e stray from its road by more than a crossing needs? (See kStrayShare.)
  auto strays = [&](std::size_t e) {
    const XY a = nodes[net.edges[e].first], b = nodes[net.edges[e].second];
    double off2 = 0, sigma = std::numeric_limits<double>::infinity();
    for (auto i = s.start[e]; i < s.start[e + 1]; ++i)
      off2 = std::max(off2, point_segment_distance2(grid::place(g, points, s.samples[i]), a, b));
    const double off = std::sqrt(off2);
    if (off <= noise) return false;
    for_each_quad(p, net, e, [&](std::uint32_t q) { sigma = std::min(sigma, stretch_of(q)); });
    return off > kStrayShare * sigma * s.clearance[e];
  };

  // The first step looks at every edge; later ones only around the vertices the last one moved.
  std::vector<std::uint32_t> scope_quads;  // empty: everywhere
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  std::vector<std::uint32_t> list;
  for (;; ++report.steps) {
    util::check_stop();
    std::vector<Box> suspects;
    std::vector<std::uint32_t> suspect_quads;
    const auto first = ++stamp;  // listed[e] == first: e is among this step's suspects
    auto consider = [&](std::size_t e) {
      if (affected[e]) suspect[e] = strays(e);
      if (!suspect[e]) return;
      listed[e] = first;
      suspects.push_back(box_of(e));
      for_each_quad(p, net, e, [&](std::uint32_t q) { suspect_quads.push_back(q); });
    };
    if (scope_quads.empty()) {
      for (std::size_t e = 0; e < edges; ++e) consider(e);
    } else {
      const auto in_scope = ++stamp;
      for (auto q : scope_quads)
        edges_in(q, [&](std::uint32_t e) {
          if (edge_mark[e] != in_scope) edge_mark[e] = in_scope, consider(e);
        });
    }
    if (report.steps == 0) report.suspects = suspects.size();
    if (suspects.empty()) break;
    // Candidates: the edges in the suspects' quads and the quads around them (a chord that
    // strays crosses only what runs close to its road).
    const auto near = mark_with_ring(suspect_quads);
    const auto taken = ++stamp;
    std::vector<Box> candidates;
    for (std::uint32_t q = 0; q < g.quads.size(); ++q)
      if (quad_mark[q] == near)
        edges_in(q, [&](std::uint32_t e) {
          if (edge_mark[e] != taken) edge_mark[e] = taken, candidates.push_back(box_of(e));
        });
    pairs.clear();
    CGAL::box_intersection_d(suspects.begin(), suspects.end(), candidates.begin(), candidates.end(),
                             [&](const Box& a, const Box& c) {
                               const auto e = a.handle(), f = c.handle();
                               if (e == f || (listed[f] == first && f < e)) return;  // both listed: once
                               if (!affected[e] && !affected[f]) return;   // unchanged: did not cross
                               const auto [a0, a1] = net.edges[e];
                               const auto [b0, b1] = net.edges[f];
                               if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1) return;
                               if (!segments_cross(nodes[a0], nodes[a1], nodes[b0], nodes[b1])) return;
                               if (segment_distance(net.nodes[a0], net.nodes[a1], net.nodes[b0], net.nodes[b1]) <= touching) return;
                               pairs.emplace_back(e, f);
                             });
    if (pairs.empty()) break;
    if (report.steps >= max_steps || std::chrono::steady_clock::now() >= until) {
      report.left = pairs.size();
      break;
    }
    // Smooth the quads under both roads of every new crossing, and rings around them when that
    // did not suffice.
    const auto moving = ++stamp;
    list.clear();
    auto move = [&](std::uint32_t v) {
      if (vertex_mark[v] != moving) vertex_mark[v] = moving, list.push_back(v);
    };
    for (const auto& [e, f] : pairs)
      for (auto edge : {e, f})
        for_each_quad(p, net, edge, [&](std::uint32_t q) {
          for (auto v : g.quads[q].corners) move(v);
        });
    for (int ring = 0; ring < report.steps / kStepsPerRing; ++ring) {
      const auto size = list.size();
      for (std::size_t i = 0; i < size; ++i)
        for (const auto& nb : g.neighbors[list[i]])
          if (nb.kind == grid::Neighbor::Kind::vertex) move(nb.index);
    }
    smooth_vertices(p, points, list);
    // Snapping moved the T-junctions on moved coarse sides too.
    for (const auto& t : g.tjunctions) {
      const auto& c = g.quads[t.coarse_quad].corners;
      if (vertex_mark[c[t.side]] == moving || vertex_mark[c[(t.side + 1) % 4]] == moving) move(t.vertex);
    }
    // What changed: the edges in the quads at moved vertices (nodes placed again, strays
    // measured again); the next step looks one ring further for the partners of their chords.
    std::vector<std::uint32_t> changed;
    const auto quad_seen = ++stamp;
    for (auto v : list)
      quads_at(v, [&](std::uint32_t q) {
        if (quad_mark[q] != quad_seen) quad_mark[q] = quad_seen, changed.push_back(q);
      });
    for (auto q : changed) stretch[q] = std::numeric_limits<double>::quiet_NaN();
    std::fill(affected.begin(), affected.end(), 0);
    for (auto q : changed)
      edges_in(q, [&](std::uint32_t e) {
        if (affected[e]) return;
        affected[e] = 1;
        for (auto n : {net.edges[e].first, net.edges[e].second}) nodes[n] = grid::place(g, points, p.embeddings[n]);
      });
    const auto ring = mark_with_ring(changed);
    scope_quads.clear();
    for (std::uint32_t q = 0; q < g.quads.size(); ++q)
      if (quad_mark[q] == ring) scope_quads.push_back(q);
  }
  return report;
}

}  // namespace tourmap::deform
