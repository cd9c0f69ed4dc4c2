#include "metro/bend_reduction.hpp"

#include "metro/layout_chains.hpp"
#include "metro/octilinear_shapes.hpp"
#include "metro/segment_geometry.hpp"
#include "metro/warp.hpp"
#include "util/thread_cpu_clock.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <numeric>

namespace tourmap::metro {
namespace {

// The budget is this thread's CPU time: the same layout on a busy machine as on an idle one.
using Clock = util::ThreadCpuClock;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Box {
  double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  void add(XY p) {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  bool overlaps(const Box& o, double pad) const {
    return x0 - pad <= o.x1 && o.x0 <= x1 + pad && y0 - pad <= o.y1 && o.y0 <= y1 + pad;
  }
};

Box box_of(const std::vector<XY>& pts) {
  Box b;
  for (const auto& p : pts) b.add(p);
  return b;
}

double dist2(XY a, XY b) { return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y); }

// Bends and the sum of their turns (45-degree steps) of a polyline. Octilinear pieces compare
// by direction index; others by angle.
std::pair<int, int> turns_of(const std::vector<XY>& pts, double eps) {
  int bends = 0, turn45 = 0;
  int last = -2;  // octant of the previous piece, -1 if not octilinear
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const XY d{pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y};
    const int o = octant_of(d, eps);
    if (i >= 2) {
      int steps = 0;
      if (o >= 0 && last >= 0) {
        const int diff = std::abs(o - last);
        steps = std::min(diff, 8 - diff);
      } else {
        const XY p{pts[i - 1].x - pts[i - 2].x, pts[i - 1].y - pts[i - 2].y};
        const double turn = std::abs(std::remainder(std::atan2(d.y, d.x) - std::atan2(p.y, p.x), 2 * M_PI));
        steps = turn <= 0.0175 ? 0 : std::max(1, static_cast<int>(std::lround(turn / (M_PI / 4))));
      }
      if (steps > 0) ++bends, turn45 += steps;
    }
    last = o;
  }
  return {bends, turn45};
}

// A chain end at an anchor: which chain, and whether it is the chain's `a` end.
struct ChainEnd {
  std::uint32_t chain;
  bool at_a;
  bool operator==(const ChainEnd&) const = default;
};

// A candidate drawing of one chain: its polyline (corners) and its inner nodes' positions.
struct Drawn {
  std::vector<XY> shape;
  std::vector<XY> inner;
  std::vector<double> arc;  // arc length of a, the inner nodes, b
  double cost = 0;          // without the clearance term
  double clear = 0;         // clearance (capped at the gap asked for) when installed
};

// The edge of `chain` (drawn as `d`) that runs through point `at` on segment `seg` (1-based).
std::uint32_t edge_at(const LayoutChain& chain, const Drawn& d, std::size_t seg, XY at) {
  double s = 0;
  for (std::size_t i = 1; i < seg; ++i) s += std::sqrt(dist2(d.shape[i - 1], d.shape[i]));
  s += std::sqrt(dist2(d.shape[seg - 1], at));
  const auto it = std::upper_bound(d.arc.begin() + 1, d.arc.end() - 1, s);
  return chain.edges[static_cast<std::size_t>(it - d.arc.begin()) - 1];
}

std::pair<std::uint32_t, std::uint32_t> ordered(std::uint32_t a, std::uint32_t b) { return {std::min(a, b), std::max(a, b)}; }

// A drawing not yet worked out: its polyline, a lower bound of its cost (the bends, turns and
// lengths, without the displacement) and how to place the inner stations.
struct Proposal {
  enum Placement { share, given, near_targets } placement = share;
  double bound = 0;
  std::vector<XY> shape;
  std::vector<double> arc;  // for `given`
};

class BendSearch;

// A cycle's chain (it starts and ends at one anchor) split in two halves at a middle station,
// which becomes an anchor of the search: else nothing could move its stations (a loop such as
// Heathrow's, drawn tiny by the router, would stay tiny). `split_at` gets those stations.
std::vector<LayoutChain> split_cycles(std::vector<LayoutChain> chains, std::vector<std::uint32_t>& split_at) {
  std::vector<LayoutChain> out;
  for (auto& chain : chains) {
    if (chain.a != chain.b || chain.edges.size() < 2) {
      out.push_back(std::move(chain));
      continue;
    }
    const std::size_t s = chain.edges.size() / 2;  // edges [0, s) and [s, n)
    const std::uint32_t x = chain.inner[s - 1];
    split_at.push_back(x);
    LayoutChain first, second;
    first.a = chain.a, first.b = x, second.a = x, second.b = chain.b;
    const auto cut = [](const auto& v, std::size_t from, std::size_t to) {
      return std::vector<typename std::decay_t<decltype(v)>::value_type>(v.begin() + static_cast<std::ptrdiff_t>(from),
                                                                          v.begin() + static_cast<std::ptrdiff_t>(to));
    };
    first.edges = cut(chain.edges, 0, s), first.forward = cut(chain.forward, 0, s), first.inner = cut(chain.inner, 0, s - 1);
    second.edges = cut(chain.edges, s, chain.edges.size()), second.forward = cut(chain.forward, s, chain.edges.size());
    second.inner = cut(chain.inner, s, chain.inner.size());
    out.push_back(std::move(first));
    out.push_back(std::move(second));
  }
  return out;
}

// The drawings of one chain in increasing order of cost, worked out lazily: a proposal is
// evaluated only when its bound could beat the best evaluated one.
class CandidateQueue {
 public:
  CandidateQueue(const BendSearch& search, std::size_t chain, std::vector<Proposal> proposals);
  bool next(Drawn& out);

 private:
  const BendSearch& search_;
  std::size_t chain_;
  std::vector<Proposal> proposals_;
  std::size_t next_ = 0;
  std::vector<Drawn> heap_;
};

class BendSearch {
  friend class CandidateQueue;

 public:
  BendSearch(const LayoutGraph& g, Layout& layout, const BendReductionParams& params)
      : g_(g), layout_(layout), p_(params), chains_(split_cycles(layout_chains(g), split_at_)) {}

  void run(BendReductionReport& report);

 private:
  void setup();
  void fit_targets();
  double chain_cost(std::size_t c, const Drawn& d) const;
  // An edge `ratio` times its target length: the target is a minimum (eq. 5.4), so longer
  // costs less than shorter (the geography may ask for a long edge).
  double length_cost(double ratio) const {
    const double r = std::log(ratio);
    return p_.w_length * r * r * (r < 0 ? 1.0 : p_.longer_share);
  }
  // Bends and sharp turns of chain c. In the polish phase a chain may not gain any over what
  // it had when the phase began (each one beyond costs as much as a bend did before any
  // displacement), but one fewer is worth only what it was in the first phase: the polish
  // keeps the bends and brings the geography back; it does not buy a bend with the geography
  // (Chicago lost its 17th bend there for 1.2 points of displacement, when the time allowed).
  double turn_cost(std::size_t c, int bends, int turn45) const {
    double cost = p_.w_bend * bends + p_.w_turn * (turn45 - bends);
    if (!bend_base_.empty()) {
      cost += kNoMoreBends * std::max(0, bends - bend_base_[c].first);
      cost += kNoMoreBends * std::max(0, turn45 - bend_base_[c].second);
    }
    return cost;
  }
  static constexpr double kNoMoreBends = 1000.0;
  // A clearance (or an edge length) below the gap asked for, linear in the shortfall.
  double gap_cost(double clear) const { return p_.w_gap * std::max(0.0, gap_ - clear) / gap_; }
  void refresh_clearances();
  Drawn drawn_along(std::size_t c, const std::vector<XY>& shape) const;
  Drawn drawn_near_targets(std::size_t c, const std::vector<XY>& shape) const;
  void run_phase(BendReductionReport& report, Clock::time_point until, int max_rounds);
  CandidateQueue candidates(std::size_t c) const;
  Drawn materialize(std::size_t c, Proposal& p) const;
  double shape_bound(std::size_t c, const std::vector<XY>& shape, const std::vector<double>* arc) const;
  double clearance(std::size_t c, const Drawn& d, bool& crossing_ok, double floor = 0) const;
  double anchor_clearance(std::uint32_t v, bool* ok = nullptr) const;
  std::vector<double> port_angles(std::uint32_t v, std::size_t c = SIZE_MAX, const std::vector<XY>* shape = nullptr) const;
  bool ports_ok(std::uint32_t v, std::size_t c = SIZE_MAX, const std::vector<XY>* shape = nullptr) const;
  void install(std::size_t c, Drawn d);
  bool redraw_chain(std::size_t c);
  bool move_anchor(std::uint32_t v);
  std::vector<XY> move_candidates(std::uint32_t v) const;
  bool try_move(std::uint32_t v, XY to, double& gain);
  bool out_of_time() const { return Clock::now() > deadline_; }
  std::size_t total_bends() const;
  void write_back();

  const LayoutGraph& g_;
  Layout& layout_;
  BendReductionParams p_;  // a copy: the polish phase changes its weights
  std::vector<std::uint32_t> split_at_;               // stations where a cycle was split (see split_cycles)
  std::vector<LayoutChain> chains_;
  std::vector<Drawn> drawn_;                          // per chain, as it is now
  std::vector<Box> box_;                              // per chain
  std::vector<char> fixed_, pending_, dirty_;         // per chain
  std::vector<std::uint32_t> chain_of_;               // per node: its chain if inner, else -1
  std::vector<std::vector<ChainEnd>> ends_;           // per node: chain ends at it (anchors)
  std::vector<std::vector<ChainEnd>> order_;          // per anchor: ends counter-clockwise at the start
  std::vector<double> gap_floor_;                     // per chain: clearance asked for (<= gap_)
  std::vector<double> anchor_floor_;                  // per anchor
  std::vector<double> anchor_clear_;                  // per anchor: its clearance now
  std::vector<double> edge_floor_;                    // per edge: the shortest it may get
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> crossings_;  // chain pairs crossing at the start...
  std::set<std::pair<std::uint32_t, std::uint32_t>> crossing_edges_;   // ...and the edge pairs that cross there
  std::vector<XY> target_;                            // per node: geography fitted to the layout
  std::vector<double> chain_target_;                  // per chain: sum of target lengths
  double unit_ = 1, eps_ = 1e-9, gap_ = 0;
  // How close a chain or anchor may come to another whose floor is `floor`: not below it (strict),
  // or, while bends come first, not below the smallest floor anywhere (the drawing's minimum
  // clearance never drops).
  bool strict_pairs_ = false;
  double global_floor_ = 0;
  double pair_floor(double floor) const { return (strict_pairs_ ? std::min(floor, gap_) : std::min(floor, global_floor_)) - eps_; }
  Clock::time_point deadline_;
  std::vector<std::pair<int, int>> bend_base_;  // per chain in the polish: (bends, 45-degree turns) at its start
};

void BendSearch::fit_targets() {
  // Least-squares similarity (scale, rotation, translation) of the geography onto the layout:
  // the fit the displacement figure uses.
  const Helmert fit = fit_helmert(g_.pos, layout_.pos);
  target_.resize(g_.pos.size());
  for (std::size_t v = 0; v < g_.pos.size(); ++v) target_[v] = fit.apply(g_.pos[v]);
}

double BendSearch::chain_cost(std::size_t c, const Drawn& d) const {
  const auto& chain = chains_[c];
  auto [bends, turn45] = turns_of(d.shape, eps_);
  double cost = turn_cost(c, bends, turn45);
  for (std::size_t i = 0; i < chain.inner.size(); ++i)
    cost += p_.w_displacement * dist2(d.inner[i], target_[chain.inner[i]]) / (unit_ * unit_);
  for (std::size_t i = 0; i < chain.edges.size(); ++i) {
    const double len = std::max(d.arc[i + 1] - d.arc[i], 1e-9 * unit_);
    cost += length_cost(len / g_.min_length[chain.edges[i]]) + gap_cost(len);
  }
  return cost;
}

Drawn BendSearch::drawn_along(std::size_t c, const std::vector<XY>& shape) const {
  const auto& chain = chains_[c];
  Drawn d;
  d.shape = shape;
  const double len = polyline_length(shape);
  double acc = 0;
  d.arc.push_back(0);
  for (std::size_t i = 0; i + 1 < chain.edges.size(); ++i) {
    acc += g_.min_length[chain.edges[i]];
    d.arc.push_back(len * acc / chain_target_[c]);
  }
  d.arc.push_back(len);
  d.inner = points_at_lengths(shape, d.arc);
  d.cost = chain_cost(c, d);
  return d;
}

// Ways to redraw chain c (best first): the whole chain with the fewest bends between its
// anchors (stations at their share of the target length), or one stretch between two corners of
// its drawing, up to kMaxSpan corners apart, replaced by such a shape (stations on it keep
// their relative places). An anchor that moved takes the stretch next to it along.
// Chain c along `shape` with each inner station at the point of the shape nearest its
// geographic target, pushed apart (in order) so that every edge keeps min_edge_share of its
// target length; the share placement when they do not fit.
Drawn BendSearch::drawn_near_targets(std::size_t c, const std::vector<XY>& shape) const {
  const auto& chain = chains_[c];
  const std::size_t k = chain.inner.size();
  const double len = polyline_length(shape);
  std::vector<double> seg_start(shape.size(), 0.0);
  for (std::size_t i = 1; i < shape.size(); ++i) seg_start[i] = seg_start[i - 1] + std::sqrt(dist2(shape[i - 1], shape[i]));
  std::vector<double> arc(k + 2, 0.0);
  arc[k + 1] = len;
  for (std::size_t i = 0; i < k; ++i) {
    const XY t = target_[chain.inner[i]];
    double best = kInf;
    for (std::size_t j = 1; j < shape.size(); ++j) {
      const XY a = shape[j - 1], b = shape[j];
      const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
      const double u = l2 > 0 ? std::clamp(((t.x - a.x) * dx + (t.y - a.y) * dy) / l2, 0.0, 1.0) : 0.0;
      const double d2 = dist2(t, {a.x + u * dx, a.y + u * dy});
      if (d2 < best) best = d2, arc[i + 1] = seg_start[j - 1] + u * std::sqrt(l2);
    }
  }
  // Pushed apart to the gap asked for where the chain has room, else to each edge's floor.
  const std::vector<double> nearest = arc;
  bool fits = false;
  for (const bool roomy : {true, false}) {
    const auto gap = [&](std::size_t e) { return roomy ? std::max(gap_, edge_floor_[chain.edges[e]]) : edge_floor_[chain.edges[e]]; };
    arc = nearest;
    for (std::size_t i = 1; i <= k; ++i) arc[i] = std::max(arc[i], arc[i - 1] + gap(i - 1));
    for (std::size_t i = k; i >= 1; --i) arc[i] = std::min(arc[i], arc[i + 1] - gap(i));
    fits = true;
    for (std::size_t i = 1; i <= k + 1; ++i) fits &= arc[i] >= arc[i - 1] + gap(i - 1) - eps_;
    if (fits) break;
  }
  if (!fits) return drawn_along(c, shape);
  Drawn d;
  d.shape = shape;
  d.arc = std::move(arc);
  d.inner = points_at_lengths(shape, d.arc);
  d.cost = chain_cost(c, d);
  return d;
}

double BendSearch::shape_bound(std::size_t c, const std::vector<XY>& shape, const std::vector<double>* arc) const {
  const auto [bends, turn45] = turns_of(shape, eps_);
  double bound = turn_cost(c, bends, turn45);
  const auto& edges = chains_[c].edges;
  if (arc) {
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const double len = std::max((*arc)[e + 1] - (*arc)[e], 1e-9 * unit_);
      bound += length_cost(len / g_.min_length[edges[e]]) + gap_cost(len);
    }
  }
  return bound;
}

Drawn BendSearch::materialize(std::size_t c, Proposal& p) const {
  if (p.placement == Proposal::share) return drawn_along(c, p.shape);
  if (p.placement == Proposal::near_targets) return drawn_near_targets(c, p.shape);
  Drawn d;
  d.shape = std::move(p.shape);
  d.arc = std::move(p.arc);
  d.inner = points_at_lengths(d.shape, d.arc);
  d.cost = chain_cost(c, d);
  return d;
}

CandidateQueue::CandidateQueue(const BendSearch& search, std::size_t chain, std::vector<Proposal> proposals)
    : search_(search), chain_(chain), proposals_(std::move(proposals)) {
  std::sort(proposals_.begin(), proposals_.end(), [](const Proposal& x, const Proposal& y) { return x.bound < y.bound; });
}

bool CandidateQueue::next(Drawn& out) {
  const auto later = [](const Drawn& x, const Drawn& y) { return x.cost > y.cost; };
  while (next_ < proposals_.size() && (heap_.empty() || heap_.front().cost > proposals_[next_].bound)) {
    heap_.push_back(search_.materialize(chain_, proposals_[next_++]));
    std::push_heap(heap_.begin(), heap_.end(), later);
  }
  if (heap_.empty()) return false;
  std::pop_heap(heap_.begin(), heap_.end(), later);
  out = std::move(heap_.back());
  heap_.pop_back();
  return true;
}

// Ways to redraw chain c: the whole chain with the fewest bends between its anchors (stations
// at their share of the target length, or near their geography), or one stretch between two
// corners of its drawing, up to kMaxSpan corners apart, replaced by such a shape (stations on
// it keep their relative places). An anchor that moved takes the stretch next to it along.
CandidateQueue BendSearch::candidates(std::size_t c) const {
  constexpr std::size_t kMaxSpan = 6;
  const auto& chain = chains_[c];
  const Drawn& cur = drawn_[c];
  const XY pa = layout_.pos[chain.a], pb = layout_.pos[chain.b];
  const bool a_moved = dist2(cur.shape.front(), pa) > eps_ * eps_, b_moved = dist2(cur.shape.back(), pb) > eps_ * eps_;
  std::vector<Proposal> out;
  for (auto& s : octilinear_shapes(pa, pb, eps_)) {
    const double len = polyline_length(s.corners);
    if (len < p_.min_length_share * chain_target_[c]) continue;
    const double bound = shape_bound(c, s.corners, nullptr);  // stations not placed yet: no length term
    if (!chain.inner.empty()) out.push_back({Proposal::near_targets, bound, s.corners, {}});
    out.push_back({Proposal::share, bound, std::move(s.corners), {}});
  }
  const auto& S = cur.shape;
  const std::size_t m = S.size() - 1;
  std::vector<double> corner_arc(m + 1, 0.0);
  for (std::size_t k = 1; k <= m; ++k) corner_arc[k] = corner_arc[k - 1] + std::sqrt(dist2(S[k - 1], S[k]));
  const double old_len = corner_arc[m];
  for (std::size_t i = 0; i < m; ++i) {
    if (a_moved && i != 0) break;
    for (std::size_t j = i + 1; j <= std::min(m, i + kMaxSpan); ++j) {
      if (b_moved && j != m) continue;
      if (i == 0 && j == m) continue;                                 // the whole chain: above
      if (j - i < 2 && !(i == 0 && a_moved) && !(j == m && b_moved)) continue;  // one straight piece: nothing to gain
      const XY P = i == 0 ? pa : S[i], Q = j == m ? pb : S[j];
      const double span = corner_arc[j] - corner_arc[i];
      for (auto& shape : octilinear_shapes(P, Q, eps_)) {
        const double new_span = polyline_length(shape.corners);
        const double len = old_len - span + new_span;
        if (len < p_.min_length_share * chain_target_[c]) continue;
        std::vector<XY> pts(S.begin(), S.begin() + static_cast<std::ptrdiff_t>(i));
        pts.insert(pts.end(), shape.corners.begin(), shape.corners.end());
        pts.insert(pts.end(), S.begin() + static_cast<std::ptrdiff_t>(j) + 1, S.end());
        Proposal p{Proposal::given, 0, simplify_polyline(pts, eps_), {}};
        p.arc.reserve(cur.arc.size());
        for (double s_old : cur.arc)
          p.arc.push_back(s_old <= corner_arc[i]   ? s_old
                          : s_old >= corner_arc[j] ? s_old - span + new_span
                                                   : corner_arc[i] + (s_old - corner_arc[i]) * new_span / span);
        p.arc.front() = 0;
        p.arc.back() = len;
        bool short_edge = false;
        for (std::size_t e = 0; e < chain.edges.size(); ++e)
          short_edge |= p.arc[e + 1] - p.arc[e] < edge_floor_[chain.edges[e]] - eps_;
        if (short_edge) continue;
        p.bound = shape_bound(c, p.shape, &p.arc);
        out.push_back(std::move(p));
      }
    }
  }
  return CandidateQueue(*this, c, std::move(out));
}

// The smallest distance (capped at gap_) between chain c drawn as `d` and every node or chain it
// does not belong to (pending chains are skipped: they are being redrawn); crossing_ok tells
// whether it crosses no chain more often, or elsewhere, than at the start. Stops early (with a
// value below `floor`) once the answer is known to be too small.
double BendSearch::clearance(std::size_t c, const Drawn& d, bool& crossing_ok, double floor) const {
  const auto& chain = chains_[c];
  const Box box = box_of(d.shape);
  double gap2 = gap_ * gap_, pair_min = gap_ * gap_;
  const double floor2 = floor * floor;
  crossing_ok = true;
  for (std::size_t e = 0; e < chain.edges.size(); ++e)
    if (d.arc[e + 1] - d.arc[e] < edge_floor_[chain.edges[e]] - eps_) {
      crossing_ok = false;
      return 0;
    }
  const auto mine = [&](std::uint32_t v) { return v == chain.a || v == chain.b; };
  // Squared distance from p to the polyline, updating gap2 (segments beyond gap2 skipped cheaply).
  const auto near_shape = [&](XY p, const std::vector<XY>& shape) {
    const double r = std::sqrt(gap2);
    for (std::size_t i = 1; i < shape.size(); ++i) {
      const XY a = shape[i - 1], b = shape[i];
      if (p.x < std::min(a.x, b.x) - r || p.x > std::max(a.x, b.x) + r || p.y < std::min(a.y, b.y) - r ||
          p.y > std::max(a.y, b.y) + r)
        continue;
      gap2 = std::min(gap2, point_segment_distance2(p, a, b));
    }
  };
  // The chain must not touch itself: no piece turning back, no two pieces meeting (its edges
  // would cross or overlap one another).
  const auto& sh = d.shape;
  for (std::size_t i = 2; i < sh.size(); ++i) {
    const XY u{sh[i - 1].x - sh[i - 2].x, sh[i - 1].y - sh[i - 2].y}, w{sh[i].x - sh[i - 1].x, sh[i].y - sh[i - 1].y};
    if (std::abs(u.x * w.y - u.y * w.x) <= eps_ * (std::abs(u.x) + std::abs(u.y) + std::abs(w.x) + std::abs(w.y)) &&
        u.x * w.x + u.y * w.y < 0) {
      crossing_ok = false;
      return 0;
    }
  }
  for (std::size_t i = 1; i < sh.size(); ++i)
    for (std::size_t k = i + 2; k < sh.size(); ++k)
      if (segment_contact(sh[i - 1], sh[i], sh[k - 1], sh[k], eps_).kind != SegmentContact::none) {
        crossing_ok = false;
        return 0;
      }
  for (std::size_t o = 0; o < chains_.size(); ++o) {
    if (o == c || pending_[o]) continue;
    // A pair that crossed at the start must still cross as often (a geographic crossing lost is
    // a line moved round the end of another): it is checked even when far apart.
    const auto expected = crossings_.find(ordered(static_cast<std::uint32_t>(c), static_cast<std::uint32_t>(o)));
    const int must_cross = expected == crossings_.end() ? 0 : expected->second;
    if (!must_cross && !box.overlaps(box_[o], gap_)) continue;
    const auto& other = chains_[o];
    const auto& os = drawn_[o].shape;
    int crossings = 0;
    const Box& ob = box_[o];
    for (std::size_t i = 1; i < d.shape.size(); ++i) {
      const XY a = d.shape[i - 1], b = d.shape[i];
      if (std::max(a.x, b.x) + eps_ < ob.x0 || std::min(a.x, b.x) - eps_ > ob.x1 || std::max(a.y, b.y) + eps_ < ob.y0 ||
          std::min(a.y, b.y) - eps_ > ob.y1)
        continue;
      for (std::size_t k = 1; k < os.size(); ++k) {
        auto hit = segment_contact(d.shape[i - 1], d.shape[i], os[k - 1], os[k], eps_);
        if (hit.kind == SegmentContact::none) continue;
        if (hit.kind == SegmentContact::point) {
          bool at_shared_anchor = false;
          for (auto v : {other.a, other.b})
            if (mine(v) && dist2(hit.at, layout_.pos[v]) <= eps_ * eps_ * 4) at_shared_anchor = true;
          if (at_shared_anchor) continue;
          // A crossing is kept only between edges that crossed at the start: the geography's.
          if (!crossing_edges_.count(ordered(edge_at(chain, d, i, hit.at), edge_at(other, drawn_[o], k, hit.at)))) {
            crossing_ok = false;
            return 0;
          }
          ++crossings;
        } else {
          crossing_ok = false;
          return 0;
        }
      }
    }
    if (crossings != must_cross) {
      crossing_ok = false;
      return 0;
    }
    // Clearance: the other chain's nodes against this one, this one's inner nodes against it.
    // Neither side may get closer than its own floor allows: the other's anchors theirs, the
    // other chain its own (else a chain with a low floor could crowd one with a high one).
    const double before_pair = gap2;
    for (auto v : {other.a, other.b})
      if (!mine(v)) {
        gap2 = gap_ * gap_;
        near_shape(layout_.pos[v], d.shape);
        for (const auto& q : d.inner) gap2 = std::min(gap2, dist2(q, layout_.pos[v]));
        const double need = pair_floor(anchor_floor_[v]);
        if (need > 0 && gap2 < need * need) {
          crossing_ok = false;
          return 0;
        }
        pair_min = std::min(pair_min, gap2);
      }
    gap2 = gap_ * gap_;
    for (const auto& p : drawn_[o].inner) {
      near_shape(p, d.shape);
      for (const auto& q : d.inner) gap2 = std::min(gap2, dist2(p, q));
    }
    for (const auto& q : d.inner) near_shape(q, os);
    const double need = pair_floor(gap_floor_[o]);
    if (need > 0 && gap2 < need * need) {
      crossing_ok = false;
      return 0;
    }
    gap2 = std::min({gap2, pair_min, before_pair});
    pair_min = gap_ * gap_;
    if (gap2 < floor2) return std::sqrt(gap2);
  }
  // Within the chain: each station against the chain's edges it is not on (a sharp turn at a
  // station brings the previous station close to the next edge).
  const std::size_t n = chain.edges.size();
  if (n >= 2) {
    std::vector<double> corner_arc(sh.size(), 0.0);
    for (std::size_t i = 1; i < sh.size(); ++i) corner_arc[i] = corner_arc[i - 1] + std::sqrt(dist2(sh[i - 1], sh[i]));
    // Squared distance from p to the drawing between arc lengths s0 and s1.
    const auto to_stretch = [&](XY p, double s0, double s1) {
      double best = kInf;
      for (std::size_t i = 1; i < sh.size(); ++i) {
        const double a0 = corner_arc[i - 1], a1 = corner_arc[i];
        if (a1 <= s0 || a0 >= s1 || a1 - a0 <= 0) continue;
        const double t0 = (std::max(a0, s0) - a0) / (a1 - a0), t1 = (std::min(a1, s1) - a0) / (a1 - a0);
        const XY u = sh[i - 1], w = sh[i];
        best = std::min(best, point_segment_distance2(p, {u.x + t0 * (w.x - u.x), u.y + t0 * (w.y - u.y)},
                                                      {u.x + t1 * (w.x - u.x), u.y + t1 * (w.y - u.y)}));
      }
      return best;
    };
    for (std::size_t i = 0; i <= n; ++i) {
      const XY p = i == 0 ? layout_.pos[chain.a] : i == n ? layout_.pos[chain.b] : d.inner[i - 1];
      if (i >= 2) gap2 = std::min(gap2, to_stretch(p, 0, d.arc[i - 1]));
      if (i + 2 <= n) gap2 = std::min(gap2, to_stretch(p, d.arc[i + 1], d.arc[n]));
    }
  }
  return std::sqrt(gap2);
}

// The smallest distance (capped at gap_) from anchor v to nodes it is not joined to and to
// chains that do not end at it. With `ok`: false when v is closer to a chain than that chain's
// floor.
double BendSearch::anchor_clearance(std::uint32_t v, bool* ok) const {
  const XY p = layout_.pos[v];
  Box box;
  box.add(p);
  double gap = gap_;
  for (std::size_t o = 0; o < chains_.size(); ++o) {
    if (!box.overlaps(box_[o], gap_)) continue;
    const auto& chain = chains_[o];
    const auto& d = drawn_[o];
    const bool incident = chain.a == v || chain.b == v;
    if (!incident) {
      double pair = gap_;
      for (std::size_t i = 1; i < d.shape.size(); ++i) pair = std::min(pair, point_segment_distance(p, d.shape[i - 1], d.shape[i]));
      if (ok && pair < pair_floor(gap_floor_[o])) *ok = false;
      gap = std::min(gap, pair);
    }
    for (std::size_t i = 0; i < d.inner.size(); ++i) {
      const bool joined = (chain.a == v && i == 0) || (chain.b == v && i + 1 == d.inner.size());
      if (!joined) gap = std::min(gap, std::sqrt(dist2(p, d.inner[i])));
    }
    for (auto w : {chain.a, chain.b}) {
      const bool joined = incident && chain.edges.size() == 1;
      if (w != v && !joined) gap = std::min(gap, std::sqrt(dist2(p, layout_.pos[w])));
    }
  }
  return gap;
}

// The directions in which the anchor's chains leave it (chain c drawn as `shape` if given).
std::vector<double> BendSearch::port_angles(std::uint32_t v, std::size_t c, const std::vector<XY>* shape) const {
  std::vector<double> angles;
  for (const auto& end : ends_[v]) {
    const auto& s = end.chain == c ? *shape : drawn_[end.chain].shape;
    const XY from = end.at_a ? s[0] : s[s.size() - 1], to = end.at_a ? s[1] : s[s.size() - 2];
    angles.push_back(std::atan2(to.y - from.y, to.x - from.x));
  }
  return angles;
}

// The anchor's chains leave in distinct directions, in the circular order of the start.
bool BendSearch::ports_ok(std::uint32_t v, std::size_t c, const std::vector<XY>* shape) const {
  const auto angles = port_angles(v, c, shape);
  const std::size_t n = angles.size();
  if (n < 2) return true;
  std::vector<std::size_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](std::size_t i, std::size_t j) { return angles[i] < angles[j]; });
  for (std::size_t i = 0; i < n; ++i) {
    const double gap = std::remainder(angles[idx[(i + 1) % n]] - angles[idx[i]], 2 * M_PI);
    if (std::abs(gap) < 1e-6) return false;
  }
  if (n < 3) return true;
  const auto& want = order_[v];
  const auto first = std::find(idx.begin(), idx.end(),
                               static_cast<std::size_t>(std::find(ends_[v].begin(), ends_[v].end(), want[0]) - ends_[v].begin()));
  std::rotate(idx.begin(), first, idx.end());
  for (std::size_t i = 0; i < n; ++i)
    if (!(ends_[v][idx[i]] == want[i])) return false;
  return true;
}

void BendSearch::install(std::size_t c, Drawn d) {
  const auto& chain = chains_[c];
  for (std::size_t i = 0; i < chain.inner.size(); ++i) layout_.pos[chain.inner[i]] = d.inner[i];
  box_[c] = box_of(d.shape);
  drawn_[c] = std::move(d);
  dirty_[c] = 1;
}

void BendSearch::setup() {
  const std::size_t n = g_.pos.size();
  double target_sum = 0;
  for (double l : g_.min_length) target_sum += l;
  unit_ = g_.min_length.empty() ? 1.0 : target_sum / g_.min_length.size();
  eps_ = 1e-7 * unit_;
  chain_of_.assign(n, std::numeric_limits<std::uint32_t>::max());
  ends_.assign(n, {});
  const std::size_t m = chains_.size();
  drawn_.resize(m);
  box_.resize(m);
  fixed_.assign(m, 0);
  pending_.assign(m, 0);
  dirty_.assign(m, 0);
  chain_target_.assign(m, 0);
  double edge_sum = 0;
  for (const auto& path : layout_.paths) edge_sum += polyline_length(path);
  gap_ = p_.gap_share * p_.gap_margin * (layout_.paths.empty() ? unit_ : edge_sum / layout_.paths.size());
  // An edge is a station's clearance to the next edge along its line: it keeps the gap and
  // min_edge_share of its target length, or what it had when it started shorter.
  edge_floor_.resize(layout_.paths.size());
  for (std::size_t e = 0; e < layout_.paths.size(); ++e)
    edge_floor_[e] = std::min(polyline_length(layout_.paths[e]) - eps_, std::max(p_.min_edge_share * g_.min_length[e], gap_));
  for (std::size_t c = 0; c < m; ++c) {
    const auto& chain = chains_[c];
    for (auto v : chain.inner) chain_of_[v] = static_cast<std::uint32_t>(c);
    ends_[chain.a].push_back({static_cast<std::uint32_t>(c), true});
    ends_[chain.b].push_back({static_cast<std::uint32_t>(c), false});
    fixed_[c] = chain.a == chain.b;
    for (auto e : chain.edges) chain_target_[c] += g_.min_length[e];
    auto& d = drawn_[c];
    d.shape = simplify_polyline(chain_polyline(chain, layout_), eps_);
    if (d.shape.size() < 2) d.shape = {layout_.pos[chain.a], layout_.pos[chain.b]};
    d.arc.push_back(0);
    for (std::size_t i = 0; i < chain.edges.size(); ++i) {
      d.arc.push_back(d.arc.back() + polyline_length(layout_.paths[chain.edges[i]]));
      if (i + 1 < chain.edges.size()) d.inner.push_back(layout_.pos[chain.inner[i]]);
    }
    box_[c] = box_of(d.shape);
  }
  order_.assign(n, {});
  for (std::uint32_t v = 0; v < n; ++v) {
    const auto angles = port_angles(v);
    std::vector<std::size_t> idx(angles.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(), [&](std::size_t i, std::size_t j) { return angles[i] < angles[j]; });
    for (auto i : idx) order_[v].push_back(ends_[v][i]);
  }
  for (std::size_t c = 0; c < m; ++c)
    for (std::size_t o = c + 1; o < m; ++o) {
      if (!box_[c].overlaps(box_[o], 0)) continue;
      int hits = 0;
      const auto& s = drawn_[c].shape;
      const auto& t = drawn_[o].shape;
      for (std::size_t i = 1; i < s.size(); ++i)
        for (std::size_t k = 1; k < t.size(); ++k) {
          auto hit = segment_contact(s[i - 1], s[i], t[k - 1], t[k], eps_);
          if (hit.kind == SegmentContact::none) continue;
          bool shared = false;
          for (auto v : {chains_[o].a, chains_[o].b})
            if ((v == chains_[c].a || v == chains_[c].b) && dist2(hit.at, layout_.pos[v]) <= eps_ * eps_ * 4) shared = true;
          if (hit.kind == SegmentContact::point && !shared) {  // (an overlap is never kept: see clearance)
            ++hits;
            crossing_edges_.insert(ordered(edge_at(chains_[c], drawn_[c], i, hit.at), edge_at(chains_[o], drawn_[o], k, hit.at)));
          }
        }
      if (hits > 0) crossings_[{static_cast<std::uint32_t>(c), static_cast<std::uint32_t>(o)}] = hits;
    }
  fit_targets();
  // The floors are what the start has: measured with no floor in force (all zero), then set.
  gap_floor_.assign(m, 0);
  anchor_floor_.assign(n, 0);
  for (std::size_t c = 0; c < m; ++c) {
    drawn_[c].cost = chain_cost(c, drawn_[c]);
    bool ok = true;
    drawn_[c].clear = clearance(c, drawn_[c], ok);
  }
  anchor_clear_.assign(n, 0);
  for (std::uint32_t v = 0; v < n; ++v)
    if (!ends_[v].empty()) anchor_clear_[v] = anchor_clearance(v);
  for (std::size_t c = 0; c < m; ++c) gap_floor_[c] = drawn_[c].clear;
  anchor_floor_ = anchor_clear_;
}

// The gap asked for follows the mean edge as it is now, and every chain's and anchor's
// clearance is measured afresh (others' moves change them).
void BendSearch::refresh_clearances() {
  double edge_sum = 0;
  for (const auto& d : drawn_) edge_sum += d.arc.back();
  if (!layout_.paths.empty()) gap_ = p_.gap_share * p_.gap_margin * edge_sum / layout_.paths.size();
  for (std::size_t c = 0; c < chains_.size(); ++c) {
    bool ok = true;
    drawn_[c].clear = clearance(c, drawn_[c], ok);
    drawn_[c].cost = chain_cost(c, drawn_[c]);
    gap_floor_[c] = std::min(gap_floor_[c], drawn_[c].clear);
  }
  for (std::uint32_t v = 0; v < g_.pos.size(); ++v)
    if (!ends_[v].empty()) {
      anchor_clear_[v] = anchor_clearance(v);
      anchor_floor_[v] = std::min(anchor_floor_[v], anchor_clear_[v]);
    }
  global_floor_ = gap_;
  for (double f : gap_floor_) global_floor_ = std::min(global_floor_, f);
  for (std::uint32_t v = 0; v < g_.pos.size(); ++v)
    if (!ends_[v].empty()) global_floor_ = std::min(global_floor_, anchor_floor_[v]);
}

// Redraws chain c between its anchors as they are, when a drawing with a lower cost is valid.
bool BendSearch::redraw_chain(std::size_t c) {
  if (fixed_[c]) return false;
  const auto& chain = chains_[c];
  const double current = drawn_[c].cost + gap_cost(drawn_[c].clear);
  auto queue = candidates(c);
  for (Drawn d; queue.next(d);) {
    if (d.cost >= current - 1e-9) break;
    if (!ports_ok(chain.a, c, &d.shape) || !ports_ok(chain.b, c, &d.shape)) continue;
    bool crossing_ok = true;
    const double gap = clearance(c, d, crossing_ok, gap_floor_[c] - eps_);
    if (!crossing_ok || gap < gap_floor_[c] - eps_ || d.cost + gap_cost(gap) >= current - 1e-9) continue;
    d.clear = gap;
    install(c, std::move(d));
    gap_floor_[c] = std::max(gap_floor_[c], gap);
    return true;
  }
  return false;
}

std::vector<XY> BendSearch::move_candidates(std::uint32_t v) const {
  const XY at = layout_.pos[v];
  const double radius = p_.move_radius * unit_;
  std::vector<XY> out;
  const auto consider = [&](XY p) {
    if (dist2(p, at) <= radius * radius && dist2(p, at) > eps_ * eps_) out.push_back(p);
  };
  std::vector<XY> far;
  for (const auto& end : ends_[v]) far.push_back(layout_.pos[end.at_a ? chains_[end.chain].b : chains_[end.chain].a]);
  for (const auto& b : far)
    for (const auto& d : kOctants) {
      const double s = ((at.x - b.x) * d.x + (at.y - b.y) * d.y) / (d.x * d.x + d.y * d.y);
      if (s > 0) consider({b.x + s * d.x, b.y + s * d.y});
    }
  for (std::size_t i = 0; i < far.size(); ++i)
    for (std::size_t j = i + 1; j < far.size(); ++j)
      for (const auto& d1 : kOctants)
        for (const auto& d2 : kOctants) {
          const double det = d1.x * d2.y - d1.y * d2.x;
          if (det == 0) continue;
          const XY r{far[j].x - far[i].x, far[j].y - far[i].y};
          const double s = (r.x * d2.y - r.y * d2.x) / det, t = (r.x * d1.y - r.y * d1.x) / det;
          if (s > 0 && t > 0) consider({far[i].x + s * d1.x, far[i].y + s * d1.y});
        }
  for (double step : {0.1, 0.25}) {
    for (const auto& d : kOctants) consider({at.x + step * unit_ * d.x, at.y + step * unit_ * d.y});
  }
  return out;
}

// Moves anchor v to `to` and redraws its chains; keeps it when valid and cheaper by `gain`.
bool BendSearch::try_move(std::uint32_t v, XY to, double& gain) {
  const XY from = layout_.pos[v];
  std::vector<std::size_t> mine;
  for (const auto& end : ends_[v])
    if (std::find(mine.begin(), mine.end(), end.chain) == mine.end()) mine.push_back(end.chain);
  std::vector<Drawn> saved;
  double before = p_.w_displacement * dist2(from, target_[v]) / (unit_ * unit_) + gap_cost(anchor_clear_[v]);
  for (auto c : mine) {
    saved.push_back(drawn_[c]);
    before += drawn_[c].cost + gap_cost(drawn_[c].clear);
  }
  std::vector<double> floors;
  for (auto c : mine) floors.push_back(gap_floor_[c]);
  layout_.pos[v] = to;
  for (auto c : mine) pending_[c] = 1;
  double after = p_.w_displacement * dist2(to, target_[v]) / (unit_ * unit_);
  bool ok = true;
  for (std::size_t i = 0; i < mine.size() && ok; ++i) {
    const auto c = mine[i];
    const auto& chain = chains_[c];
    const std::uint32_t other = chain.a == v ? chain.b : chain.a;
    bool placed = false;
    auto queue = candidates(c);
    for (Drawn d; queue.next(d);) {
      if (before - (after + d.cost) <= gain) break;  // cannot beat the best move found
      if (!ports_ok(other, c, &d.shape)) continue;
      bool crossing_ok = true;
      const double gap = clearance(c, d, crossing_ok, gap_floor_[c] - eps_);
      if (!crossing_ok || gap < gap_floor_[c] - eps_) continue;
      after += d.cost + gap_cost(gap);
      d.clear = gap;
      install(c, std::move(d));
      pending_[c] = 0;
      gap_floor_[c] = std::max(gap_floor_[c], gap);
      placed = true;
      break;
    }
    ok = placed;
  }
  const double anchor_gap = ok ? anchor_clearance(v, &ok) : 0;
  after += gap_cost(anchor_gap);
  if (ok && ports_ok(v) && anchor_gap >= anchor_floor_[v] - eps_ && before - after > gain) {
    gain = before - after;
    for (auto c : mine) pending_[c] = 0;
    anchor_floor_[v] = std::max(anchor_floor_[v], anchor_gap);
    anchor_clear_[v] = anchor_gap;
    return true;
  }
  layout_.pos[v] = from;
  for (std::size_t i = 0; i < mine.size(); ++i) {
    pending_[mine[i]] = 0;
    install(mine[i], std::move(saved[i]));
    gap_floor_[mine[i]] = floors[i];
  }
  return false;
}

bool BendSearch::move_anchor(std::uint32_t v) {
  for (const auto& end : ends_[v])
    if (fixed_[end.chain]) return false;
  if (ends_[v].empty()) return false;
  // Rank candidates by what they can be expected to give: bends they can remove (a chain
  // becomes straight when the anchor lies on an octilinear line through its other end) and the
  // anchor's own displacement.
  auto cands = move_candidates(v);
  std::vector<std::pair<double, XY>> ranked;
  for (const auto& p : cands) {
    double est = p_.w_displacement * dist2(p, target_[v]) / (unit_ * unit_);
    for (const auto& end : ends_[v]) {
      const auto& chain = chains_[end.chain];
      const XY b = layout_.pos[end.at_a ? chain.b : chain.a];
      est += p_.w_bend * (octant_of({b.x - p.x, b.y - p.y}, eps_) >= 0 ? 0 : 1);
    }
    ranked.push_back({est, p});
  }
  std::sort(ranked.begin(), ranked.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  if (ranked.size() > p_.evaluations_per_anchor) ranked.resize(p_.evaluations_per_anchor);
  double gain = 1e-6;
  for (const auto& [est, p] : ranked) {
    if (out_of_time()) return false;
    if (try_move(v, p, gain)) return true;  // first improvement: candidates come best estimate first
  }
  return false;
}

std::size_t BendSearch::total_bends() const {
  std::size_t bends = 0;
  for (const auto& d : drawn_) bends += turns_of(d.shape, eps_).first;
  // A reader sees the turn where a cycle was split as a bend of its chain.
  for (auto v : split_at_) {
    const auto angles = port_angles(v);
    if (angles.size() == 2 && std::abs(std::remainder(angles[0] - angles[1], 2 * M_PI)) < M_PI - 1e-6) ++bends;
  }
  return bends;
}

void BendSearch::write_back() {
  for (std::size_t c = 0; c < chains_.size(); ++c) {
    if (!dirty_[c]) continue;
    const auto& chain = chains_[c];
    const auto& d = drawn_[c];
    for (std::size_t i = 0; i < chain.edges.size(); ++i) {
      // Without near-repeated points: a path's first piece gives the edge's direction at a station.
      auto path = simplify_polyline(polyline_between(d.shape, d.arc[i], d.arc[i + 1]), eps_);
      path.front() = layout_.pos[i == 0 ? chain.a : chain.inner[i - 1]];
      path.back() = layout_.pos[i + 1 == chain.edges.size() ? chain.b : chain.inner[i]];
      if (!chain.forward[i]) std::reverse(path.begin(), path.end());
      layout_.paths[chain.edges[i]] = std::move(path);
    }
  }
}

void BendSearch::run_phase(BendReductionReport& report, Clock::time_point until, int max_rounds) {
  deadline_ = until;
  for (std::size_t c = 0; c < chains_.size(); ++c) drawn_[c].cost = chain_cost(c, drawn_[c]);
  for (int round = 0; round < max_rounds && !out_of_time(); ++round) {
    ++report.rounds;
    fit_targets();
    refresh_clearances();
    std::size_t changes = 0;
    for (std::size_t c = 0; c < chains_.size() && !out_of_time(); ++c)
      if (redraw_chain(c)) ++changes, ++report.reshaped;
    for (std::uint32_t v = 0; v < g_.pos.size() && !out_of_time(); ++v)
      if (ends_[v].size() != 0 && chain_of_[v] == std::numeric_limits<std::uint32_t>::max() && move_anchor(v))
        ++changes, ++report.moved;
    if (changes == 0) break;
  }
}

void BendSearch::run(BendReductionReport& report) {
  const auto wall_started = std::chrono::steady_clock::now();
  const auto started = Clock::now();
  const auto budget = std::chrono::microseconds(static_cast<long long>(p_.time_limit_ms * 1000));
  deadline_ = started + budget;
  setup();
  report.chains = chains_.size();
  report.bends_before = total_bends();
  // Phase 1: bends first, the geography pulling weakly. Phase 2: the geography back where it
  // costs no bend (see turn_cost).
  run_phase(report, started + std::chrono::duration_cast<std::chrono::microseconds>(budget * (1 - p_.polish_share)),
            p_.max_rounds);
  const bool phase1_timed_out = out_of_time();
  for (const auto& d : drawn_) bend_base_.push_back(turns_of(d.shape, eps_));
  p_.w_bend *= p_.polish_bend_factor;
  p_.w_turn *= p_.polish_bend_factor;
  p_.w_displacement = p_.w_displacement_polish;
  p_.w_gap = p_.w_gap_polish;
  strict_pairs_ = true;
  run_phase(report, started + budget, p_.polish_max_rounds);
  report.timed_out = phase1_timed_out || out_of_time();
  write_back();
  report.bends_after = total_bends();
  report.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall_started).count();
}

}  // namespace

void reduce_bends(const LayoutGraph& g, Layout& layout, const BendReductionParams& params, BendReductionReport* report) {
  BendReductionReport local;
  if (g.edges.empty() || layout.paths.size() != g.edges.size()) {
    if (report) *report = local;
    return;
  }
  BendSearch search(g, layout, params);
  search.run(local);
  if (report) *report = local;
}

}  // namespace tourmap::metro
