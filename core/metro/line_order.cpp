#include "metro/line_order.hpp"

#include "util/elapsed.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>

namespace tourmap::metro {
namespace {

using util::Clock;
using util::ms_since;

// The direction in which edge e leaves node v in the drawing (radians), from the first point of
// its path that differs from v's.
double leaving_angle(const LayoutGraph& g, const Layout& L, std::uint32_t e, std::uint32_t v) {
  const auto& path = L.paths[e];
  const bool from_first = g.edges[e].first == v;
  const XY at = from_first ? path.front() : path.back();
  for (std::size_t k = 1; k < path.size(); ++k) {
    const XY p = from_first ? path[k] : path[path.size() - 1 - k];
    if (p.x != at.x || p.y != at.y) return std::atan2(p.y - at.y, p.x - at.x);
  }
  return 0;
}

// What the model needs of the network: per node, the edges that carry each line there.
struct Network {
  const LayoutGraph& g;
  const Layout& L;
  std::vector<std::vector<std::uint32_t>> lines;  // per edge, sorted
  std::vector<std::map<std::uint32_t, std::vector<std::uint32_t>>> carry;  // per node: line -> its edges there

  Network(const LayoutGraph& graph, const Layout& layout) : g(graph), L(layout), carry(graph.pos.size()) {
    lines.resize(g.edges.size());
    for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
      lines[e] = e < g.edge_lines.size() ? g.edge_lines[e] : std::vector<std::uint32_t>{};
      std::sort(lines[e].begin(), lines[e].end());
      lines[e].erase(std::unique(lines[e].begin(), lines[e].end()), lines[e].end());
      for (auto l : lines[e])
        for (auto v : {g.edges[e].first, g.edges[e].second})
          if (g.edges[e].first != g.edges[e].second || v == g.edges[e].first) carry[v][l].push_back(e);
    }
  }
  // Travelling along e into v is e's own direction (first -> second).
  bool into(std::uint32_t e, std::uint32_t v) const { return g.edges[e].second == v; }
  bool away(std::uint32_t e, std::uint32_t v) const { return g.edges[e].first == v; }
  std::uint32_t other(std::uint32_t e, std::uint32_t v) const {
    return g.edges[e].first == v ? g.edges[e].second : g.edges[e].first;
  }
  // Arriving at v along s, is exit x further left than exit y? (0: neither, same direction)
  int more_left(std::uint32_t v, std::uint32_t s, std::uint32_t x, std::uint32_t y) const {
    const double base = leaving_angle(g, L, s, v);
    const auto ccw = [&](std::uint32_t e) {
      double a = leaving_angle(g, L, e, v) - base;
      while (a <= 0) a += 2 * M_PI;
      while (a > 2 * M_PI) a -= 2 * M_PI;
      return a;
    };
    const double ax = ccw(x), ay = ccw(y);
    // Arriving against s's leaving direction, a larger counter-clockwise angle from it is a
    // turn further to the left.
    if (std::abs(ax - ay) < 1e-9) return 0;
    return ax > ay ? 1 : -1;
  }
};

// A line's passes through a node: the pairs of its edges there (one for a line running
// through, none at its end, every pair where it branches).
std::vector<std::pair<std::uint32_t, std::uint32_t>> passes(const std::vector<std::uint32_t>& edges) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (std::size_t j = i + 1; j < edges.size(); ++j) out.push_back({edges[i], edges[j]});
  return out;
}

// One place where the order of a pair of lines (a < b) matters, at node v:
//   same: both run s -> x; a crossing when a is left of b arriving on s but not leaving on x;
//   part: they share s and part (a to xa, b to xb); a crossing unless the one on the left
//         arriving on s takes the exit further left (`a_left`: a should be left on s).
struct Constraint {
  enum Kind { same, part } kind;
  std::uint32_t v, a, b, s, x;
  bool a_left = false;
};

std::vector<Constraint> constraints_of(const Network& n) {
  std::vector<Constraint> out;
  for (std::uint32_t v = 0; v < n.carry.size(); ++v) {
    const auto& here = n.carry[v];
    for (auto ia = here.begin(); ia != here.end(); ++ia)
      for (auto ib = std::next(ia); ib != here.end(); ++ib) {
        const auto a = ia->first, b = ib->first;
        for (auto [a1, a2] : passes(ia->second))
          for (auto [b1, b2] : passes(ib->second)) {
            if ((a1 == b1 && a2 == b2) || (a1 == b2 && a2 == b1)) {
              out.push_back({Constraint::same, v, a, b, a1, a2});
              continue;
            }
            // Shared edge s, and each one's other edge.
            std::uint32_t s, xa, xb;
            if (a1 == b1) s = a1, xa = a2, xb = b2;
            else if (a1 == b2) s = a1, xa = a2, xb = b1;
            else if (a2 == b1) s = a2, xa = a1, xb = b2;
            else if (a2 == b2) s = a2, xa = a1, xb = b1;
            else continue;  // no common edge: the geometry decides
            const int left = n.more_left(v, s, xa, xb);
            if (left == 0) continue;
            out.push_back({Constraint::part, v, a, b, s, 0, left > 0});
          }
      }
  }
  return out;
}

// Position of each line on each edge, from an order.
using Positions = std::vector<std::map<std::uint32_t, std::size_t>>;

Positions positions_of(const std::vector<std::vector<std::uint32_t>>& order) {
  Positions pos(order.size());
  for (std::size_t e = 0; e < order.size(); ++e)
    for (std::size_t i = 0; i < order[e].size(); ++i) pos[e][order[e][i]] = i;
  return pos;
}

// Is a left of b on e in the frame of travel along e into v (`into`) or away from v?
bool left_in_travel(const Positions& pos, const Network& n, std::uint32_t e, std::uint32_t v, bool arriving,
                    std::uint32_t a, std::uint32_t b) {
  const bool canonical_left = pos[e].at(a) < pos[e].at(b);
  const bool canonical = arriving ? n.into(e, v) : n.away(e, v);
  return canonical ? canonical_left : !canonical_left;
}

LineCrossings count(const Network& n, const std::vector<Constraint>& cs, const std::vector<std::vector<std::uint32_t>>& order) {
  const auto pos = positions_of(order);
  LineCrossings out;
  for (const auto& c : cs) {
    const bool on_s = left_in_travel(pos, n, c.s, c.v, true, c.a, c.b);
    if (c.kind == Constraint::part) {
      out.crossings += on_s != c.a_left;
      continue;
    }
    const bool on_x = left_in_travel(pos, n, c.x, c.v, false, c.a, c.b);
    out.crossings += on_s != on_x;
    const auto gap = [&](std::uint32_t e) {
      const auto i = pos[e].at(c.a), j = pos[e].at(c.b);
      return i > j ? i - j : j - i;
    };
    out.separations += (gap(c.s) == 1) != (gap(c.x) == 1);
  }
  return out;
}

// The heuristic: each pair's order on an edge voted at both ends by where the pair parts,
// following the track they share (left stays left along it) until they do; lines sorted by
// their votes.
int vote(const Network& n, std::uint32_t e, std::uint32_t toward, std::uint32_t a, std::uint32_t b) {
  // Votes are in e's own frame; travelling along e towards `toward` is that frame or its mirror,
  // and left stays left along shared track, so the sign holds all the way.
  const int sign = n.into(e, toward) ? 1 : -1;
  std::uint32_t s = e, v = toward;
  for (std::size_t step = 0; step <= n.g.edges.size(); ++step) {
    const auto ia = n.carry[v].find(a), ib = n.carry[v].find(b);
    if (ia == n.carry[v].end() || ib == n.carry[v].end()) return 0;
    if (ia->second.size() != 2 || ib->second.size() != 2) return 0;  // an end or a branch
    const auto xa = ia->second[0] == s ? ia->second[1] : ia->second[0];
    const auto xb = ib->second[0] == s ? ib->second[1] : ib->second[0];
    if (xa == xb) {
      v = n.other(xa, v);
      s = xa;
      continue;
    }
    return sign * n.more_left(v, s, xa, xb);
  }
  return 0;
}

std::vector<std::vector<std::uint32_t>> heuristic_order(const Network& n) {
  std::vector<std::vector<std::uint32_t>> order(n.lines.size());
  for (std::uint32_t e = 0; e < n.lines.size(); ++e) {
    const auto& ls = n.lines[e];
    std::map<std::uint32_t, int> score;
    for (std::size_t i = 0; i < ls.size(); ++i)
      for (std::size_t j = i + 1; j < ls.size(); ++j) {
        const int v = vote(n, e, n.g.edges[e].second, ls[i], ls[j]) + vote(n, e, n.g.edges[e].first, ls[i], ls[j]);
        score[ls[i]] += v;
        score[ls[j]] -= v;
      }
    order[e] = ls;
    std::stable_sort(order[e].begin(), order[e].end(), [&](auto x, auto y) { return score[x] > score[y]; });
  }
  return order;
}

// The exact model (see the header).
struct Model {
  MipModel mip;
  std::vector<std::size_t> base;  // per edge: its first pair column
  double constant = 0;            // objective = constant + mip objective

  // Column of the pair (i < j: indices into the edge's sorted lines).
  int column(const Network& n, std::uint32_t e, std::size_t i, std::size_t j) const {
    const std::size_t k = n.lines[e].size();
    // Pairs of an edge in row-major order: (0,1), (0,2), ..., (1,2), ...
    const std::size_t before = i * k - i * (i + 1) / 2;
    return static_cast<int>(base[e] + before + (j - i - 1));
  }
  // "a left of b on e, travelling into v (or away)" = alpha + beta * y.
  std::pair<double, std::pair<int, double>> left(const Network& n, std::uint32_t e, std::uint32_t v, bool arriving,
                                                 std::uint32_t a, std::uint32_t b) const {
    const auto& ls = n.lines[e];
    const std::size_t ia = static_cast<std::size_t>(std::lower_bound(ls.begin(), ls.end(), a) - ls.begin());
    const std::size_t ib = static_cast<std::size_t>(std::lower_bound(ls.begin(), ls.end(), b) - ls.begin());
    const int col = column(n, e, std::min(ia, ib), std::max(ia, ib));
    // y = "the lower line index is left" in e's own frame.
    bool plain = ia < ib;
    if (!(arriving ? n.into(e, v) : n.away(e, v))) plain = !plain;
    return plain ? std::pair{0.0, std::pair{col, 1.0}} : std::pair{1.0, std::pair{col, -1.0}};
  }
};

Model build_model(const Network& n, const std::vector<Constraint>& cs, const std::vector<std::vector<std::uint32_t>>& start) {
  Model m;
  m.base.resize(n.lines.size());
  const auto pos = positions_of(start);
  for (std::uint32_t e = 0; e < n.lines.size(); ++e) {
    m.base[e] = m.mip.columns();
    const auto& ls = n.lines[e];
    for (std::size_t i = 0; i < ls.size(); ++i)
      for (std::size_t j = i + 1; j < ls.size(); ++j)
        m.mip.add_column(0, 1, 0, true, pos[e].at(ls[i]) < pos[e].at(ls[j]) ? 1 : 0);
    // Transitivity: 0 <= y_ij + y_jk - y_ik <= 1.
    for (std::size_t i = 0; i < ls.size(); ++i)
      for (std::size_t j = i + 1; j < ls.size(); ++j)
        for (std::size_t k = j + 1; k < ls.size(); ++k)
          m.mip.add_row({{m.column(n, e, i, j), 1}, {m.column(n, e, j, k), 1}, {m.column(n, e, i, k), -1}}, 0, 1);
  }
  std::vector<std::pair<int, double>> cost;  // linear costs on pair columns
  for (const auto& c : cs) {
    const auto [alpha_s, ys] = m.left(n, c.s, c.v, true, c.a, c.b);
    if (c.kind == Constraint::part) {
      // Crossing = (a_left ? 1 - left_s : left_s).
      if (c.a_left) m.constant += 1 - alpha_s, cost.push_back({ys.first, -ys.second});
      else m.constant += alpha_s, cost.push_back(ys);
      continue;
    }
    const auto [alpha_x, yx] = m.left(n, c.x, c.v, false, c.a, c.b);
    // z >= left_s - left_x and z >= left_x - left_s.
    const bool start_crosses = (alpha_s + ys.second * m.mip.start[static_cast<std::size_t>(ys.first)]) !=
                               (alpha_x + yx.second * m.mip.start[static_cast<std::size_t>(yx.first)]);
    const int z = m.mip.add_column(0, 1, 1, false, start_crosses ? 1 : 0);
    m.mip.add_row({{z, 1}, {ys.first, -ys.second}, {yx.first, yx.second}}, alpha_s - alpha_x, 1e30);
    m.mip.add_row({{z, 1}, {ys.first, ys.second}, {yx.first, -yx.second}}, alpha_x - alpha_s, 1e30);
  }
  for (auto [col, v] : cost) m.mip.cost[static_cast<std::size_t>(col)] += v;
  return m;
}

std::vector<std::vector<std::uint32_t>> order_from(const Network& n, const Model& m, const std::vector<double>& x) {
  std::vector<std::vector<std::uint32_t>> order(n.lines.size());
  for (std::uint32_t e = 0; e < n.lines.size(); ++e) {
    const auto& ls = n.lines[e];
    std::vector<int> rights(ls.size(), 0);  // how many lines each one is left of
    for (std::size_t i = 0; i < ls.size(); ++i)
      for (std::size_t j = i + 1; j < ls.size(); ++j) {
        const bool i_left = x[static_cast<std::size_t>(m.column(n, e, i, j))] > 0.5;
        ++rights[i_left ? i : j];
      }
    std::vector<std::size_t> idx(ls.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::stable_sort(idx.begin(), idx.end(), [&](auto p, auto q) { return rights[p] > rights[q]; });
    for (auto i : idx) order[e].push_back(ls[i]);
  }
  return order;
}

}  // namespace

LineCrossings count_line_crossings(const LayoutGraph& g, const Layout& layout,
                                   const std::vector<std::vector<std::uint32_t>>& order) {
  const Network n(g, layout);
  return count(n, constraints_of(n), order);
}

LineOrder order_lines(const LayoutGraph& g, const Layout& layout, const MipSolveFn& mip, const LineOrderParams& params) {
  const auto started = Clock::now();
  LineOrder out;
  const Network n(g, layout);
  const auto cs = constraints_of(n);
  out.order = heuristic_order(n);
  const auto start = count(n, cs, out.order);
  out.report.heuristic_crossings = start.crossings;
  for (const auto& ls : n.lines) out.report.pairs += ls.size() * (ls.size() - (ls.empty() ? 0 : 1)) / 2;
  out.report.method = out.report.pairs == 0 ? "none" : "heuristic";
  if (out.report.pairs > 0 && start.crossings > 0 && mip && out.report.pairs <= params.max_pairs) {
    const auto model = build_model(n, cs, out.order);
    auto solved = mip(model.mip, params.time_limit_s, 0.0);
    if (solved.x.size() == model.mip.columns() && max_violation(model.mip, solved.x) < 1e-6) {
      auto order = order_from(n, model, solved.x);
      if (count(n, cs, order).crossings <= start.crossings) {
        out.order = std::move(order);
        out.report.method = solved.status == "optimal" ? "exact" : "best_found";
      }
      out.report.lower_bound = std::max(0.0, std::ceil(model.constant + solved.bound - 1e-6));
    }
  } else if (start.crossings == 0) {
    out.report.method = out.report.pairs == 0 ? "none" : "exact";  // nothing to improve
  }
  const auto final = count(n, cs, out.order);
  out.report.crossings = final.crossings;
  out.report.separations = final.separations;
  if (out.report.method == "exact") out.report.lower_bound = static_cast<double>(final.crossings);
  out.report.time_ms = ms_since(started);
  return out;
}

}  // namespace tourmap::metro
