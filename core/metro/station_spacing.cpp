#include "metro/station_spacing.hpp"

#include "metro/grid_chains.hpp"
#include "metro/layout_quality.hpp"
#include "metro/lp_solve.hpp"
#include "metro/segment_geometry.hpp"
#include "metro/station_gap.hpp"
#include "util/elapsed.hpp"
#include "util/stop.hpp"
#include "util/thread_cpu_clock.hpp"

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace tourmap::metro {
namespace {

using util::Clock;
using util::ms_since;

constexpr double kFree = 1e30;  // an unbounded column or row side (CBC's infinity)
constexpr double kDiag = 0.70710678118654752440;
// The octilinear unit directions, counter-clockwise from east.
constexpr std::array<XY, 8> kDir = {XY{1, 0},  XY{kDiag, kDiag},   XY{0, 1},  XY{-kDiag, kDiag},
                                    XY{-1, 0}, XY{-kDiag, -kDiag}, XY{0, -1}, XY{kDiag, -kDiag}};

double dot(XY a, XY b) { return a.x * b.x + a.y * b.y; }
XY minus(XY a, XY b) { return {a.x - b.x, a.y - b.y}; }
double dist(XY a, XY b) { return std::hypot(a.x - b.x, a.y - b.y); }

// The octilinear direction of a -> b, or -1 when it has none (or no length).
int direction_of(XY a, XY b) {
  if (a.x == b.x && a.y == b.y) return -1;
  const double q = std::atan2(b.y - a.y, b.x - a.x) / (M_PI / 4);
  const double r = std::round(q);
  if (std::abs(q - r) > 1e-6) return -1;
  return (static_cast<int>(r) % 8 + 8) % 8;
}

struct Segment {
  std::uint32_t p, q;  // point ids
  std::uint32_t edge;
  int dir;             // of p -> q
};

// The layout as points (stations first, then bend points) and octilinear segments.
struct Drawing {
  std::size_t stations = 0;
  std::vector<XY> pt;
  std::vector<Segment> seg;
  std::vector<std::vector<std::uint32_t>> edge_points;  // per edge, from its first node to its second
};

// None when a path is not octilinear or does not run between its nodes' positions.
std::optional<Drawing> decompose(const LayoutGraph& g, const Layout& L) {
  Drawing d;
  d.stations = L.pos.size();
  d.pt = L.pos;
  d.edge_points.resize(g.edges.size());
  for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
    std::vector<XY> path;
    for (XY p : L.paths[e])
      if (path.empty() || dist(path.back(), p) > 1e-9) path.push_back(p);
    path = octi::simplify_collinear(path);
    const auto [u, v] = g.edges[e];
    if (path.size() < 2 || dist(path.front(), L.pos[u]) > 1e-6 || dist(path.back(), L.pos[v]) > 1e-6) return std::nullopt;
    auto& ids = d.edge_points[e];
    ids.push_back(u);
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
      ids.push_back(static_cast<std::uint32_t>(d.pt.size()));
      d.pt.push_back(path[i]);
    }
    ids.push_back(v);
    for (std::size_t i = 0; i + 1 < ids.size(); ++i) {
      const int dir = direction_of(d.pt[ids[i]], d.pt[ids[i + 1]]);
      if (dir < 0) return std::nullopt;
      d.seg.push_back({ids[i], ids[i + 1], e, dir});
    }
  }
  return d;
}

Layout layout_of(const Drawing& d, const std::vector<XY>& pt, const Layout& like) {
  Layout L = like;
  L.pos.assign(pt.begin(), pt.begin() + static_cast<std::ptrdiff_t>(d.stations));
  for (std::size_t e = 0; e < d.edge_points.size(); ++e) {
    L.paths[e].clear();
    for (auto id : d.edge_points[e]) L.paths[e].push_back(pt[id]);
  }
  return L;
}

// The octilinear direction w that separates point set `a` from `b` best now: the largest
// min over pairs of w.(a_i - b_j); (direction, that value).
std::pair<int, double> best_separation(const std::vector<XY>& a, const std::vector<XY>& b) {
  std::pair<int, double> best{0, -std::numeric_limits<double>::infinity()};
  for (int w = 0; w < 8; ++w) {
    double worst = std::numeric_limits<double>::infinity();
    for (XY p : a)
      for (XY q : b) worst = std::min(worst, dot(kDir[w], minus(p, q)));
    if (worst > best.second) best = {w, worst};
  }
  return best;
}

double mean_edge(const Layout& L) {
  double total = 0;
  for (const auto& path : L.paths)
    for (std::size_t i = 1; i < path.size(); ++i) total += dist(path[i - 1], path[i]);
  return L.paths.empty() ? 0.0 : total / L.paths.size();
}

struct Measure {
  double gap = 0;  // smallest gap / mean edge
  std::vector<std::pair<std::size_t, std::size_t>> crossings;  // pairs of edges, sorted
  std::size_t order_violations = 0;
  bool octilinear = true;
};

Measure measure(const LayoutGraph& g, const Layout& L) {
  Measure m;
  const double mean = mean_edge(L);
  m.gap = mean > 0 ? min_station_gap(g, L) / mean : 0.0;
  m.crossings = crossing_path_pairs(L.paths, g.edges);
  m.order_violations = count_order_violations(g, L);
  for (const auto& path : L.paths)
    for (std::size_t i = 1; i < path.size(); ++i) m.octilinear = m.octilinear && direction_of(path[i - 1], path[i]) >= 0;
  return m;
}

// One round's program around drawing `d` (mean edge `mean`).
struct Program {
  MipModel model;
  int scale = -1, shift = -1;  // columns: the similarity's scale, its x shift (y: the next)
  std::vector<int> column;     // per point: its first move column (x+, x-, y+, y-)
  std::size_t gap_pairs = 0, segment_pairs = 0;
};

// A linear expression over the columns, and a constant.
struct Expr {
  std::vector<std::pair<int, double>> terms;
  double constant = 0;
};

// expr += f * (w . point). A point is where it is now after a free similarity (scale and
// shift: the whole map may grow), plus a move: four columns per point (x+, x-, y+, y-), each
// in [0, trust], so |move| needs no rows of its own.
void add_point(Expr& e, const Program& prog, const Drawing& d, std::uint32_t point, XY w, double f) {
  const int c = prog.column[point];
  e.terms.push_back({prog.scale, f * dot(w, d.pt[point])});
  if (w.x != 0) e.terms.insert(e.terms.end(), {{prog.shift, f * w.x}, {c, f * w.x}, {c + 1, -f * w.x}});
  if (w.y != 0) e.terms.insert(e.terms.end(), {{prog.shift + 1, f * w.y}, {c + 2, f * w.y}, {c + 3, -f * w.y}});
}

// expr += w . (a - b)
void add_difference(Expr& e, const Program& prog, const Drawing& d, XY w, std::uint32_t a, std::uint32_t b) {
  add_point(e, prog, d, a, w, 1);
  add_point(e, prog, d, b, w, -1);
}

// lo <= expr <= hi, unless the expression is constant (only points that stay).
void add_row(Program& prog, Expr e, double lo, double hi) {
  if (e.terms.empty()) return;
  prog.model.add_row(std::move(e.terms), lo <= -kFree ? lo : lo - e.constant, hi >= kFree ? hi : hi - e.constant);
}

using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 2, std::size_t, CGAL::Box_intersection_d::ID_EXPLICIT>;

// A box around a segment, grown by `pad` on every side.
Box segment_box(const Drawing& d, std::size_t i, double pad) {
  const XY a = d.pt[d.seg[i].p], b = d.pt[d.seg[i].q];
  double lo[2] = {std::min(a.x, b.x) - pad, std::min(a.y, b.y) - pad};
  double hi[2] = {std::max(a.x, b.x) + pad, std::max(a.y, b.y) + pad};
  return Box(lo, hi, i);
}

// Candidate pairs by box overlap (CGAL's box intersection: near linear, where all pairs would
// be quadratic: an import may hold 20,000 edges). Sorted, so the program's rows keep one order.
// Stations with segments whose box comes within `radius`:
std::vector<std::pair<std::uint32_t, std::size_t>> station_segment_candidates(const Drawing& d, double radius) {
  std::vector<Box> stations, segments;
  for (std::uint32_t v = 0; v < d.stations; ++v) {
    double lo[2] = {d.pt[v].x - radius, d.pt[v].y - radius}, hi[2] = {d.pt[v].x + radius, d.pt[v].y + radius};
    stations.emplace_back(lo, hi, v);
  }
  for (std::size_t i = 0; i < d.seg.size(); ++i) segments.push_back(segment_box(d, i, 0));
  std::vector<std::pair<std::uint32_t, std::size_t>> out;
  CGAL::box_intersection_d(stations.begin(), stations.end(), segments.begin(), segments.end(),
                           [&](const Box& v, const Box& s) { out.push_back({static_cast<std::uint32_t>(v.handle()), s.handle()}); });
  std::sort(out.begin(), out.end());
  return out;
}

// Segment pairs whose boxes come within `radius` of each other (i < j):
std::vector<std::pair<std::size_t, std::size_t>> segment_pair_candidates(const Drawing& d, double radius) {
  std::vector<Box> segments;
  for (std::size_t i = 0; i < d.seg.size(); ++i) segments.push_back(segment_box(d, i, radius / 2));
  std::vector<std::pair<std::size_t, std::size_t>> out;
  CGAL::box_self_intersection_d(segments.begin(), segments.end(),
                                [&](const Box& a, const Box& b) { out.push_back(std::minmax(a.handle(), b.handle())); });
  std::sort(out.begin(), out.end());
  return out;
}

Program build_program(const LayoutGraph& g, const Drawing& d, double mean, const SpacingParams& p) {
  Program prog;
  auto& m = prog.model;
  const double trust = p.trust * mean, tau = p.gap_share * p.margin;
  prog.scale = m.add_column(0.8, 1.25, 0, false, 1);
  prog.shift = m.add_column(-kFree, kFree, 0, false, 0);
  m.add_column(-kFree, kFree, 0, false, 0);
  prog.column.assign(d.pt.size(), -1);
  for (std::uint32_t i = 0; i < d.pt.size(); ++i) {
    const double w = i < d.stations ? p.w_station : p.w_bend_point;
    prog.column[i] = m.add_column(0, trust, w, false, 0);
    for (int k = 1; k < 4; ++k) m.add_column(0, trust, w, false, 0);
  }
  const int mean_col = m.add_column(0, kFree, 0, false, mean);

  // Segments keep their direction and a floor on their length; edges their target; the mean.
  std::vector<Expr> edge_length(g.edges.size());
  Expr total;
  for (const auto& s : d.seg) {
    const XY u = kDir[s.dir], n{-u.y, u.x};
    Expr across, along;
    add_difference(across, prog, d, n, s.q, s.p);
    add_difference(along, prog, d, u, s.q, s.p);
    add_row(prog, std::move(across), 0, 0);
    const double now = dist(d.pt[s.p], d.pt[s.q]);
    add_row(prog, along, std::min(now, p.min_segment_share * mean), kFree);
    for (auto* e : {&edge_length[s.edge], &total}) {
      e->terms.insert(e->terms.end(), along.terms.begin(), along.terms.end());
      e->constant += along.constant;
    }
  }
  for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
    double now = 0;
    for (std::size_t i = 1; i < d.edge_points[e].size(); ++i)
      now += dist(d.pt[d.edge_points[e][i - 1]], d.pt[d.edge_points[e][i]]);
    add_row(prog, std::move(edge_length[e]), std::min(now, g.min_length[e]), kFree);
  }
  for (auto& [c, v] : total.terms) v = -v;  // edges * M - sum of lengths = 0
  total.constant = -total.constant;
  total.terms.push_back({mean_col, static_cast<double>(g.edges.size())});
  add_row(prog, std::move(total), 0, 0);

  // Stations clear of the segments of edges they are not on (soft). A segment's end nearer to
  // v along w stays the nearer one (its direction is fixed), so one row per pair.
  const double gap_radius = p.pair_radius * tau * mean + 2 * trust;
  util::check_stop();
  for (const auto& [v, si] : station_segment_candidates(d, gap_radius)) {
    const auto& s = d.seg[si];
    const auto [a, b] = g.edges[s.edge];
    if (a == v || b == v) continue;
    if (point_segment_distance(d.pt[v], d.pt[s.p], d.pt[s.q]) >= gap_radius) continue;
    const int w = best_separation({d.pt[v]}, {d.pt[s.p], d.pt[s.q]}).first;
    const auto nearer = dot(kDir[w], d.pt[s.p]) >= dot(kDir[w], d.pt[s.q]) ? s.p : s.q;
    // The slack may not let the pair come closer than it is now.
    const double now = dot(kDir[w], minus(d.pt[v], d.pt[nearer]));
    const int slack = m.add_column(0, std::max(0.0, tau * mean - now), p.w_slack, false, 0);
    Expr row;
    row.terms = {{mean_col, -tau}, {slack, 1}};
    add_difference(row, prog, d, kDir[w], v, nearer);
    add_row(prog, std::move(row), 0, kFree);
    ++prog.gap_pairs;
  }

  // Segments of other edges (or apart on one edge) kept apart by what separates them now.
  const double segment_radius = p.segment_share * mean + 2 * trust;
  util::check_stop();
  for (const auto& [i, j] : segment_pair_candidates(d, segment_radius)) {
    const auto &s = d.seg[i], &t = d.seg[j];
    if (s.p == t.p || s.p == t.q || s.q == t.p || s.q == t.q) continue;  // meet at a point: directions keep them apart
    const XY a0 = d.pt[s.p], a1 = d.pt[s.q], b0 = d.pt[t.p], b1 = d.pt[t.q];
    if (segment_contact(a0, a1, b0, b1, 1e-9).kind != SegmentContact::none) continue;  // crossing now: it stays
    const double apart = std::min({point_segment_distance(a0, b0, b1), point_segment_distance(a1, b0, b1),
                                   point_segment_distance(b0, a0, a1), point_segment_distance(b1, a0, a1)});
    if (apart >= segment_radius) continue;
    const auto [w, now] = best_separation({a0, a1}, {b0, b1});
    const double need = std::clamp(std::min(now, p.segment_share * mean), 0.0, kFree);
    // The ends that are nearest along w stay the nearest (directions are fixed): one row.
    const auto a = dot(kDir[w], a0) <= dot(kDir[w], a1) ? s.p : s.q;
    const auto b = dot(kDir[w], b0) >= dot(kDir[w], b1) ? t.p : t.q;
    Expr row;
    add_difference(row, prog, d, kDir[w], a, b);
    add_row(prog, std::move(row), need, kFree);
    ++prog.segment_pairs;
  }
  return prog;
}

}  // namespace

SpacingReport space_stations(const LayoutGraph& g, Layout& layout, const SpacingParams& p) {
  const auto started = Clock::now();
  const auto cpu_started = util::ThreadCpuClock::now();
  SpacingReport report;
  Measure now = measure(g, layout);
  report.gap_before = report.gap_after = now.gap;
  if (now.gap >= p.gap_share) {
    report.status = "met";
    return report;
  }
  report.status = "no_gain";
  for (int round = 0; round < p.max_rounds; ++round) {
    util::check_stop();  // the request's deadline or client (a round may outlast the budget)
    const double left_ms =
        p.time_limit_ms - std::chrono::duration<double, std::milli>(util::ThreadCpuClock::now() - cpu_started).count();
    if (left_ms <= 0) {
      report.status = "time_limit";
      break;
    }
    auto drawing = decompose(g, layout);
    if (!drawing || !now.octilinear) {
      report.status = "skipped";
      break;
    }
    const double mean = mean_edge(layout);
    if (!(mean > 0)) {
      report.status = "skipped";
      break;
    }
    auto prog = build_program(g, *drawing, mean, p);
    report.columns = prog.model.columns();
    report.rows = prog.model.rows.size();
    ++report.rounds;
    // The round in progress may finish past the budget (CLP counts the process's CPU time, which
    // other threads advance too): a round is 5-150 ms on the shared networks.
    auto solved = solve_lp_with_clp(prog.model, left_ms / 1000.0 + 0.5);
    if (solved.x.size() != prog.model.columns()) {
      report.status = "solver";
      break;
    }
    std::vector<XY> pt(drawing->pt.size());
    for (std::uint32_t i = 0; i < pt.size(); ++i) {
      const auto& x = solved.x;
      const auto* move = &x[static_cast<std::size_t>(prog.column[i])];
      const double scale = x[static_cast<std::size_t>(prog.scale)];
      const auto shift = static_cast<std::size_t>(prog.shift);
      pt[i] = {scale * drawing->pt[i].x + x[shift] + move[0] - move[1],
               scale * drawing->pt[i].y + x[shift + 1] + move[2] - move[3]};
    }
    auto candidate = layout_of(*drawing, pt, layout);
    auto next = measure(g, candidate);
    const bool better = next.gap > now.gap + 1e-6 && next.order_violations <= now.order_violations &&
                        next.octilinear &&
                        std::includes(now.crossings.begin(), now.crossings.end(), next.crossings.begin(), next.crossings.end());
    if (!better) break;
    layout = std::move(candidate);
    now = next;
    ++report.accepted;
    report.gap_after = now.gap;
    report.status = "improved";
    if (now.gap >= p.gap_share) {
      report.status = "met";
      break;
    }
  }
  report.time_ms = ms_since(started);
  return report;
}

}  // namespace tourmap::metro
