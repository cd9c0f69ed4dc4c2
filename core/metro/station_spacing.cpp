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
#include <unordered_set>
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
  int mean = -1;               // column: the mean edge M
  std::vector<int> column;     // per point: its first move column (x+, x-, y+, y-)
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

// A box around the segment from a to b, grown by `pad` on every side.
Box segment_box(XY a, XY b, std::size_t id, double pad) {
  double lo[2] = {std::min(a.x, b.x) - pad, std::min(a.y, b.y) - pad};
  double hi[2] = {std::max(a.x, b.x) + pad, std::max(a.y, b.y) + pad};
  return Box(lo, hi, id);
}

// Candidate pairs by box overlap, in the drawing `d` with its points at `pt` (CGAL's box
// intersection: near linear, where all pairs would be quadratic: an import may hold 20,000
// edges). Sorted, so the program's rows keep one order.
// Stations with segments whose box comes within `radius`:
std::vector<std::pair<std::uint32_t, std::size_t>> station_segment_candidates(const Drawing& d, const std::vector<XY>& pt,
                                                                              double radius) {
  std::vector<Box> stations, segments;
  for (std::uint32_t v = 0; v < d.stations; ++v) {
    double lo[2] = {pt[v].x - radius, pt[v].y - radius}, hi[2] = {pt[v].x + radius, pt[v].y + radius};
    stations.emplace_back(lo, hi, v);
  }
  for (std::size_t i = 0; i < d.seg.size(); ++i) segments.push_back(segment_box(pt[d.seg[i].p], pt[d.seg[i].q], i, 0));
  std::vector<std::pair<std::uint32_t, std::size_t>> out;
  CGAL::box_intersection_d(stations.begin(), stations.end(), segments.begin(), segments.end(),
                           [&](const Box& v, const Box& s) { out.push_back({static_cast<std::uint32_t>(v.handle()), s.handle()}); });
  std::sort(out.begin(), out.end());
  return out;
}

// Segment pairs whose boxes come within `radius` of each other (i < j):
std::vector<std::pair<std::size_t, std::size_t>> segment_pair_candidates(const Drawing& d, const std::vector<XY>& pt,
                                                                         double radius) {
  std::vector<Box> segments;
  for (std::size_t i = 0; i < d.seg.size(); ++i) segments.push_back(segment_box(pt[d.seg[i].p], pt[d.seg[i].q], i, radius / 2));
  std::vector<std::pair<std::size_t, std::size_t>> out;
  CGAL::box_self_intersection_d(segments.begin(), segments.end(),
                                [&](const Box& a, const Box& b) { out.push_back(std::minmax(a.handle(), b.handle())); });
  std::sort(out.begin(), out.end());
  return out;
}

// The columns, the segments' directions and floors, the edges' targets and the mean; the
// pairs' rows come separately (gap_row, apart_row).
Program build_program(const LayoutGraph& g, const Drawing& d, double mean, const SpacingParams& p) {
  Program prog;
  auto& m = prog.model;
  const double trust = p.trust * mean;
  prog.scale = m.add_column(0.8, 1.25, 0, false, 1);
  prog.shift = m.add_column(-kFree, kFree, 0, false, 0);
  m.add_column(-kFree, kFree, 0, false, 0);
  prog.column.assign(d.pt.size(), -1);
  for (std::uint32_t i = 0; i < d.pt.size(); ++i) {
    const double w = i < d.stations ? p.w_station : p.w_bend_point;
    prog.column[i] = m.add_column(0, trust, w, false, 0);
    for (int k = 1; k < 4; ++k) m.add_column(0, trust, w, false, 0);
  }
  prog.mean = m.add_column(0, kFree, 0, false, mean);

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
  total.terms.push_back({prog.mean, static_cast<double>(g.edges.size())});
  add_row(prog, std::move(total), 0, 0);
  return prog;
}

// A pair's row: lo <= terms, plus a slack column (priced) when `slack_hi` > 0.
struct PairRow {
  std::vector<std::pair<int, double>> terms;
  double lo = 0, slack_hi = 0;
};

// Station v clear of segment si of an edge it is not on (soft): w.(v - e) >= tau M, w the
// octilinear direction that separates them best now, e the segment's end nearer to v along w
// (it stays the nearer: the segment's direction is fixed), so one row per pair. The slack may
// not let the pair come closer than it is now; a pair clear of the rule now gets none.
std::optional<PairRow> gap_row(const LayoutGraph& g, const Program& prog, const Drawing& d, std::uint32_t v,
                               std::size_t si, double mean, double tau) {
  const auto& s = d.seg[si];
  const auto [a, b] = g.edges[s.edge];
  if (a == v || b == v) return std::nullopt;
  const int w = best_separation({d.pt[v]}, {d.pt[s.p], d.pt[s.q]}).first;
  const auto nearer = dot(kDir[w], d.pt[s.p]) >= dot(kDir[w], d.pt[s.q]) ? s.p : s.q;
  const double now = dot(kDir[w], minus(d.pt[v], d.pt[nearer]));
  Expr e;
  e.terms = {{prog.mean, -tau}};
  add_difference(e, prog, d, kDir[w], v, nearer);
  return PairRow{std::move(e.terms), -e.constant, std::max(0.0, tau * mean - now)};
}

// Segments i and j of other edges (or apart on one edge) kept apart by what separates them
// now: w.(a - b) >= min(now, delta M0), a and b their ends nearest along w (they stay the
// nearest: directions are fixed). None for segments that meet at a point (their directions
// keep them apart) or cross now (a geographic crossing: it stays).
std::optional<PairRow> apart_row(const Program& prog, const Drawing& d, std::size_t i, std::size_t j, double mean,
                                 const SpacingParams& p) {
  const auto &s = d.seg[i], &t = d.seg[j];
  if (s.p == t.p || s.p == t.q || s.q == t.p || s.q == t.q) return std::nullopt;
  const XY a0 = d.pt[s.p], a1 = d.pt[s.q], b0 = d.pt[t.p], b1 = d.pt[t.q];
  if (segment_contact(a0, a1, b0, b1, 1e-9).kind != SegmentContact::none) return std::nullopt;
  const auto [w, now] = best_separation({a0, a1}, {b0, b1});
  const double need = std::clamp(std::min(now, p.segment_share * mean), 0.0, kFree);
  const auto a = dot(kDir[w], a0) <= dot(kDir[w], a1) ? s.p : s.q;
  const auto b = dot(kDir[w], b0) >= dot(kDir[w], b1) ? t.p : t.q;
  Expr e;
  add_difference(e, prog, d, kDir[w], a, b);
  return PairRow{std::move(e.terms), need - e.constant, 0};
}

double segment_distance(XY a0, XY a1, XY b0, XY b1) {
  if (segment_contact(a0, a1, b0, b1, 1e-9).kind != SegmentContact::none) return 0;
  return std::min({point_segment_distance(a0, b0, b1), point_segment_distance(a1, b0, b1),
                   point_segment_distance(b0, a0, a1), point_segment_distance(b1, a0, a1)});
}

// The pairs a round's program holds, added as they are needed: those near each other at the
// start (within the rule plus the cut radius), then the ones a solution brought too close
// (a cut: the solution violates the pair's row), until a solution needs none.
class PairRows {
 public:
  PairRows(const LayoutGraph& g, const Drawing& d, const Program& prog, double mean, const SpacingParams& p)
      : g_(g), d_(d), prog_(prog), mean_(mean), p_(p), tau_(p.gap_share * p.margin) {}

  // Rows for the pairs near each other now, into the model.
  void add_initial(MipModel& m) {
    const double radius = p_.pair_radius * tau_ * mean_ + 2 * p_.cut_radius * mean_;
    for (const auto& [v, si] : station_segment_candidates(d_, d_.pt, radius))
      if (point_segment_distance(d_.pt[v], d_.pt[d_.seg[si].p], d_.pt[d_.seg[si].q]) < radius) add_gap(m, v, si);
    const double apart = p_.segment_share * mean_ + 2 * p_.cut_radius * mean_;
    for (const auto& [i, j] : segment_pair_candidates(d_, d_.pt, apart)) {
      const auto &s = d_.seg[i], &t = d_.seg[j];
      if (segment_distance(d_.pt[s.p], d_.pt[s.q], d_.pt[t.p], d_.pt[t.q]) < apart) add_apart(m, i, j);
    }
  }

  // Rows for the pairs not held yet that the points `pt` (the last solution, mean edge M)
  // bring closer than their rule; how many.
  template <typename Sink>
  std::size_t add_cuts(Sink& sink, const std::vector<XY>& pt, double M) {
    std::size_t added = 0;
    const double gap = tau_ * M * (1 - 1e-6);
    for (const auto& [v, si] : station_segment_candidates(d_, pt, gap)) {
      if (gap_pairs_.count(key(v, si))) continue;
      if (point_segment_distance(pt[v], pt[d_.seg[si].p], pt[d_.seg[si].q]) >= gap) continue;
      added += add_gap(sink, v, si);
    }
    const double apart = p_.segment_share * mean_;
    for (const auto& [i, j] : segment_pair_candidates(d_, pt, apart)) {
      if (apart_pairs_.count(key(i, j))) continue;
      const auto &s = d_.seg[i], &t = d_.seg[j];
      const double before = segment_distance(d_.pt[s.p], d_.pt[s.q], d_.pt[t.p], d_.pt[t.q]);
      if (before == 0) continue;  // crossing at the start: it stays
      const double after = segment_distance(pt[s.p], pt[s.q], pt[t.p], pt[t.q]);
      if (after >= std::min(before, apart) * (1 - 1e-6)) continue;
      added += add_apart(sink, i, j);
    }
    return added;
  }

  std::size_t gap_pairs() const { return gap_pairs_.size(); }
  std::size_t apart_pairs() const { return apart_pairs_.size(); }

 private:
  static std::uint64_t key(std::size_t a, std::size_t b) { return (static_cast<std::uint64_t>(a) << 32) | b; }

  // A sink is the model (before the first solve) or the session (cuts).
  template <typename Sink>
  bool add_gap(Sink& sink, std::uint32_t v, std::size_t si) {
    auto row = gap_row(g_, prog_, d_, v, si, mean_, tau_);
    if (!row) return false;
    gap_pairs_.insert(key(v, si));
    if (row->slack_hi > 0) row->terms.push_back({new_column(sink, row->slack_hi), 1.0});
    add(sink, row->terms, row->lo);
    return true;
  }
  template <typename Sink>
  bool add_apart(Sink& sink, std::size_t i, std::size_t j) {
    auto row = apart_row(prog_, d_, i, j, mean_, p_);
    if (!row) return false;
    apart_pairs_.insert(key(i, j));
    add(sink, row->terms, row->lo);
    return true;
  }
  // The slack starts at its upper bound: the start (no move) is then feasible.
  int new_column(MipModel& m, double hi) { return m.add_column(0, hi, p_.w_slack, false, hi); }
  int new_column(LpSession& lp, double hi) { return lp.add_column(0, hi, p_.w_slack); }
  static void add(MipModel& m, std::vector<std::pair<int, double>> terms, double lo) {
    m.add_row(std::move(terms), lo, kFree);
  }
  static void add(LpSession& lp, const std::vector<std::pair<int, double>>& terms, double lo) {
    lp.add_row(terms, lo, kFree);
  }

  const LayoutGraph& g_;
  const Drawing& d_;
  const Program& prog_;
  double mean_;
  const SpacingParams& p_;
  double tau_;
  std::unordered_set<std::uint64_t> gap_pairs_, apart_pairs_;
};

// The points of a solution: the similarity applied, then each point's move.
std::vector<XY> points_of(const Program& prog, const Drawing& d, const std::vector<double>& x) {
  std::vector<XY> pt(d.pt.size());
  const double scale = x[static_cast<std::size_t>(prog.scale)];
  const auto shift = static_cast<std::size_t>(prog.shift);
  for (std::uint32_t i = 0; i < pt.size(); ++i) {
    const auto* move = &x[static_cast<std::size_t>(prog.column[i])];
    pt[i] = {scale * d.pt[i].x + x[shift] + move[0] - move[1], scale * d.pt[i].y + x[shift + 1] + move[2] - move[3]};
  }
  return pt;
}

// One round's program around `d` (mean edge `mean`): its columns and rows, the pairs near each
// other, whatever `more` adds, then the cuts until a solution needs none. The solution's
// points, or none when the solver found none.
template <typename More>
std::optional<std::vector<XY>> solve_round(const LayoutGraph& g, const Drawing& d, double mean, const SpacingParams& p,
                                           double left_ms, SpacingReport& report, More&& more) {
  auto prog = build_program(g, d, mean, p);
  PairRows pairs(g, d, prog, mean, p);
  pairs.add_initial(prog.model);
  more(prog.model, prog);
  // The round in progress may finish past the budget (CLP counts the process's CPU time, which
  // other threads advance too).
  LpSession lp(prog.model);
  auto solved = lp.solve(left_ms / 1000.0 + 0.5);
  std::vector<XY> pt;
  for (int cut = 0; solved.status == "optimal"; ++cut) {
    pt = points_of(prog, d, solved.x);
    if (cut == p.max_cuts) break;  // the caller's acceptance test still guards the result
    const auto added = pairs.add_cuts(lp, pt, solved.x[static_cast<std::size_t>(prog.mean)]);
    if (added == 0) break;
    report.cuts += added;
    util::check_stop();
    solved = lp.resolve(left_ms / 1000.0 + 0.5);
  }
  report.columns = lp.columns();
  report.rows = lp.rows();
  if (solved.status != "optimal") return std::nullopt;
  return pt;
}

// Rows asking for each room's clearance (LabelRoom): for every segment of another edge and
// every other station near the box now, w.(q - v) - M (w.o + need) / S >= 0, with w the
// octilinear direction that separates box and obstacle best now (for an obstacle in the box,
// the one out of its far side, away from the station: London's Ravenscourt Park asked the
// Hammersmith & City line to move west onto the station, and nothing moved), q the obstacle's point
// nearest along w, o the box's corner furthest along w (px, y up; the box is o * M / S from
// the station) and need the obstacle's half width and the clearance. Soft: a slack priced
// w_room, at most what is missing now, so no obstacle comes closer to a box than it is.
// A name's box in layout units: its corners in px from the station (y up), the box at the
// station, and the neighbourhood (reach around it) whose obstacles get rows.
struct NameBox {
  std::array<XY, 4> corner;
  std::vector<XY> box;
  double x0, x1, y0, y1;
  bool near(XY a, XY b) const {
    return std::max(a.x, b.x) >= x0 && std::min(a.x, b.x) <= x1 && std::max(a.y, b.y) >= y0 && std::min(a.y, b.y) <= y1;
  }
};

NameBox name_box(const LabelRoom& label, XY at, double k, double reach) {
  NameBox b;
  b.corner = {XY{label.x0, -label.y0}, XY{label.x1, -label.y0}, XY{label.x0, -label.y1}, XY{label.x1, -label.y1}};
  for (XY c : b.corner) b.box.push_back({at.x + c.x * k, at.y + c.y * k});
  b.x0 = at.x + label.x0 * k - reach, b.x1 = at.x + label.x1 * k + reach;
  b.y0 = at.y - label.y1 * k - reach, b.y1 = at.y - label.y0 * k + reach;
  return b;
}

void add_room_rows(MipModel& m, const LayoutGraph& g, const Drawing& d, const Program& prog, double mean,
                   const std::vector<LabelRoom>& rooms, const std::vector<LabelRoom>& placed, const LabelRoomParams& rp) {
  const double k = mean / rp.scale_px;  // layout units per px now
  const double reach = rp.radius * mean;
  // Rows keeping the box of v's label (px from v, y down) clear of the lines and symbols near
  // it: all of them for a room, only those it is clear of now for a placed name (a name kept
  // must not lose its place to the room made for another; one that meets a line now was
  // placed on a side the placement will not take again anyway).
  const auto keep_clear = [&](const LabelRoom& label, bool only_clear_now) {
    const auto v = label.station;
    const XY at = d.pt[v];
    const NameBox nb = name_box(label, at, k, reach);
    const auto& corner = nb.corner;
    const auto& box = nb.box;
    const auto add = [&](std::initializer_list<std::uint32_t> ids, double need_px) {
      std::vector<XY> pts;
      for (auto id : ids) pts.push_back(d.pt[id]);
      auto [w, apart] = best_separation(pts, box);
      if (only_clear_now && apart < need_px * k) return;
      if (apart < 0) {
        // In the box now: pushed out of its far side, away from the station (towards the
        // station it would run into the station, the nearest way out often being that way).
        XY c{(box[0].x + box[3].x) / 2, (box[0].y + box[3].y) / 2}, near = pts[0];
        if (pts.size() == 2) {
          const XY ab = minus(pts[1], pts[0]);
          const double len2 = dot(ab, ab);
          const double t = len2 > 0 ? std::clamp(dot(minus(c, pts[0]), ab) / len2, 0.0, 1.0) : 0.0;
          near = {pts[0].x + t * ab.x, pts[0].y + t * ab.y};
        }
        const XY out = minus(near, at);
        for (int u = 0; u < 8; ++u)
          if (dot(kDir[u], out) > dot(kDir[w], out)) w = u;
      }
      std::uint32_t q = *ids.begin();
      for (auto id : ids)
        if (dot(kDir[w], d.pt[id]) < dot(kDir[w], d.pt[q])) q = id;
      double far = -std::numeric_limits<double>::infinity();
      for (XY c : corner) far = std::max(far, dot(kDir[w], c));
      const double coef = (far + need_px) / rp.scale_px;
      Expr e;
      e.terms = {{prog.mean, -coef}};
      add_difference(e, prog, d, kDir[w], q, v);
      const double missing = coef * mean - dot(kDir[w], minus(d.pt[q], at));
      if (missing > 0) e.terms.push_back({m.add_column(0, missing, rp.w_room, false, missing), 1.0});
      m.add_row(std::move(e.terms), -e.constant, kFree);
    };
    for (const auto& s : d.seg) {
      const auto [a, b] = g.edges[s.edge];
      if (a == v || b == v || !nb.near(d.pt[s.p], d.pt[s.q])) continue;
      std::vector<std::uint32_t> lines = g.edge_lines[s.edge];
      std::sort(lines.begin(), lines.end());
      const auto n = static_cast<double>(std::unique(lines.begin(), lines.end()) - lines.begin());
      add({s.p, s.q}, std::max(1.0, n) * rp.line_spacing_px / 2 + rp.clearance_px);
    }
    for (std::uint32_t u = 0; u < d.stations; ++u)
      if (u != v && nb.near(d.pt[u], d.pt[u])) add({u}, rp.symbol_px + rp.clearance_px);
  };
  // The placed names whose stations may move (within move_radius of a room's station).
  const double moving = rp.move_radius * mean;
  for (const auto& label : placed) {
    if (label.station >= d.stations || !rp.keep_placed) continue;
    for (const auto& room : rooms)
      if (room.station < d.stations && dist(d.pt[label.station], d.pt[room.station]) <= moving) {
        keep_clear(label, true);
        break;
      }
  }
  for (const auto& room : rooms) {
    const auto v = room.station;
    if (v >= d.stations) continue;
    keep_clear(room, false);
    const XY at = d.pt[v];
    const NameBox nb = name_box(room, at, k, reach);
    // Other names (placed ones, and the rooms after this one): both boxes move with their
    // stations, so w.(u - v) - M (max w.o_v - min w.o_u + gap) / S >= 0.
    for (const auto* list : {&placed, &rooms})
      for (const auto& other : *list) {
        if (other.station == v || other.station >= d.stations || (list == &rooms && &other <= &room)) continue;
        const XY u = d.pt[other.station];
        const NameBox ob = name_box(other, u, k, 0);
        if (!nb.near(ob.box[0], ob.box[3])) continue;
        const int w = best_separation(ob.box, nb.box).first;
        double far = -std::numeric_limits<double>::infinity(), close = std::numeric_limits<double>::infinity();
        for (XY c : nb.corner) far = std::max(far, dot(kDir[w], c));
        for (XY c : ob.corner) close = std::min(close, dot(kDir[w], c));
        const double coef = (far - close + rp.label_gap_px) / rp.scale_px;
        Expr e;
        e.terms = {{prog.mean, -coef}};
        add_difference(e, prog, d, kDir[w], other.station, v);
        const double missing = coef * mean - dot(kDir[w], minus(u, at));
        if (missing > 0) e.terms.push_back({m.add_column(0, missing, rp.w_room, false, missing), 1.0});
        m.add_row(std::move(e.terms), -e.constant, kFree);
      }
  }
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
    ++report.rounds;
    auto pt = solve_round(g, *drawing, mean, p, left_ms, report, [](MipModel&, const Program&) {});
    if (!pt) {
      report.status = "solver";
      break;
    }
    auto candidate = layout_of(*drawing, *pt, layout);
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

namespace tourmap::metro {

std::optional<Layout> make_room_for_labels(const LayoutGraph& g, const Layout& layout, const std::vector<LabelRoom>& rooms,
                                           const std::vector<LabelRoom>& placed, const LabelRoomParams& room,
                                           const SpacingParams& p) {
  if (rooms.empty()) return std::nullopt;
  auto drawing = decompose(g, layout);
  const double mean = mean_edge(layout);
  if (!drawing || !(mean > 0)) return std::nullopt;
  SpacingReport report;
  auto pt = solve_round(g, *drawing, mean, p, p.time_limit_ms, report, [&](MipModel& m, const Program& prog) {
    add_room_rows(m, g, *drawing, prog, mean, rooms, placed, room);
    // Only the points near a room move of their own (the rest moves only with the whole map,
    // its scale and shift), so that the presolved program is a fraction of a spacing round's.
    const double reach = room.move_radius * mean;
    for (std::uint32_t i = 0; i < drawing->pt.size(); ++i) {
      bool near = false;
      for (const auto& r : rooms)
        if (r.station < drawing->stations && dist(drawing->pt[i], drawing->pt[r.station]) <= reach) near = true;
      if (near) continue;
      for (int k = 0; k < 4; ++k) m.upper[static_cast<std::size_t>(prog.column[i] + k)] = 0;
    }
  });
  if (!pt) return std::nullopt;
  auto out = layout_of(*drawing, *pt, layout);
  for (const auto& path : out.paths)
    for (std::size_t i = 1; i < path.size(); ++i)
      if (direction_of(path[i - 1], path[i]) < 0) return std::nullopt;
  return out;
}

}  // namespace tourmap::metro
