#include "metro/octilinear_mip.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace tourmap::metro {
namespace {

// Octilinear sector of a direction: 0 = east, counter-clockwise in steps of 45 degrees.
int sector(XY a, XY b) {
  double s = std::atan2(b.y - a.y, b.x - a.x) / (M_PI / 4);
  return static_cast<int>(std::lround(s) % 8 + 8) % 8;
}

struct MipEdge {
  std::uint32_t a, b;
  std::uint32_t edge;        // original edge
  int start_sector, geo_sector;
  double min_length;
  std::map<int, int> alpha;  // direction -> binary column
  double start_len;
};

// Degree-2 stations that the start passes straight through, with the same lines on both
// sides, are contracted (as Nöllenburg and Wolff contract degree-2 vertices): their two
// segments become one MIP segment and the station stays at its share of it, so the MIP has
// fewer nodes and direction binaries. The merged segment's minimum length keeps each part at
// least its own share (the start, scaled to the minimum lengths, still satisfies it).
void contract_straight_stations(const LayoutGraph& g, const std::vector<XY>& pos, std::vector<MipEdge>& edges,
                                std::vector<MipPlacement>& placement) {
  const std::size_t n = g.pos.size();
  std::vector<std::vector<std::size_t>> at(n);
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (auto end : {edges[i].a, edges[i].b})
      if (end < n) at[end].push_back(i);
  auto sorted_lines = [&](std::uint32_t e) {
    auto l = g.edge_lines[e];
    std::sort(l.begin(), l.end());
    return l;
  };
  std::vector<bool> dead(edges.size(), false);
  std::vector<std::vector<std::uint32_t>> riders(edges.size());  // contracted stations on a segment
  placement.assign(n, {});
  for (std::uint32_t v = 0; v < n; ++v) {
    if (at[v].size() != 2) continue;
    std::size_t s1 = at[v][0], s2 = at[v][1];
    if (dead[s1] || dead[s2] || s1 == s2) continue;
    const MipEdge& e1 = edges[s1];
    const MipEdge& e2 = edges[s2];
    if (e1.edge == e2.edge || sorted_lines(e1.edge) != sorted_lines(e2.edge)) continue;
    const std::uint32_t a = e1.a == v ? e1.b : e1.a, b = e2.a == v ? e2.b : e2.a;
    if (a == b) continue;
    const XY da{pos[a].x - pos[v].x, pos[a].y - pos[v].y}, db{pos[b].x - pos[v].x, pos[b].y - pos[v].y};
    const double la = std::hypot(da.x, da.y), lb = std::hypot(db.x, db.y);
    if (la <= 0 || lb <= 0 || std::abs(da.x * db.y - da.y * db.x) > 1e-9 * la * lb || da.x * db.x + da.y * db.y >= 0) continue;
    // Merge: a -> v -> b becomes a -> b; each part keeps its share of the minimum length.
    MipEdge merged = e1;
    merged.a = a;
    merged.b = b;
    merged.start_len = la + lb;
    merged.start_sector = sector(pos[a], pos[b]);
    merged.geo_sector = la >= lb ? e1.geo_sector : e2.geo_sector;
    merged.min_length = std::min(merged.start_len, std::max(e1.min_length * (la + lb) / la, e2.min_length * (la + lb) / lb));
    dead[s1] = dead[s2] = true;
    edges.push_back(merged);
    dead.push_back(false);
    std::vector<std::uint32_t> on = riders[s1];
    on.insert(on.end(), riders[s2].begin(), riders[s2].end());
    on.push_back(v);
    riders.push_back(std::move(on));
    const std::size_t id = edges.size() - 1;
    for (auto end : {a, b})
      if (end < n)
        for (auto& i : at[end])
          if (i == s1 || i == s2) i = id;
  }
  std::vector<MipEdge> kept;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (dead[i]) continue;
    const auto& e = edges[i];
    const double len = std::hypot(pos[e.b].x - pos[e.a].x, pos[e.b].y - pos[e.a].y);
    for (auto v : riders[i])
      placement[v] = {true, e.a, e.b, len > 0 ? std::hypot(pos[v].x - pos[e.a].x, pos[v].y - pos[e.a].y) / len : 0.0};
    kept.push_back(e);
  }
  edges = std::move(kept);
}

// The direction of segment e leaving node v, as terms over its direction binaries (scaled).
void add_out_direction(const MipEdge& e, std::uint32_t v, double scale, std::vector<std::pair<int, double>>& terms) {
  for (auto [dir, col] : e.alpha) terms.push_back({col, scale * (e.a == v ? dir : (dir + 4) % 8)});
}

int start_out_direction(const MipEdge& e, std::uint32_t v) { return e.a == v ? e.start_sector : (e.start_sector + 4) % 8; }

// Circular order (Nöllenburg and Wolff): the segments leaving a node, taken in the geographic
// circular order of their edges, have strictly increasing directions with one wrap-around:
// dir(s_i+1) >= dir(s_i) + 1 - 8 beta_i, sum beta_i = 1. Nodes whose start breaks the order
// (the fast path reports those) are left free, so that the start stays feasible.
void add_order_rows(const LayoutGraph& g, const std::vector<XY>& pos, const std::vector<MipEdge>& edges,
                    const std::vector<std::vector<std::size_t>>& at, MipModel& m) {
  for (std::uint32_t v = 0; v < g.pos.size() && v < pos.size(); ++v) {
    std::vector<std::size_t> out = at[v];
    if (out.size() < 2) continue;
    auto geo_angle = [&](std::size_t i) {
      auto [a, b] = g.edges[edges[i].edge];
      const XY far = g.pos[a == v ? b : a];
      return std::atan2(far.y - g.pos[v].y, far.x - g.pos[v].x);
    };
    std::sort(out.begin(), out.end(), [&](std::size_t i, std::size_t j) {
      const double ai = geo_angle(i), aj = geo_angle(j);
      return ai != aj ? ai < aj : start_out_direction(edges[i], v) < start_out_direction(edges[j], v);
    });
    const std::size_t k = out.size();
    int wraps = 0;
    std::vector<double> beta_start(k, 0.0);
    for (std::size_t i = 0; i < k; ++i) {
      const int d0 = start_out_direction(edges[out[i]], v), d1 = start_out_direction(edges[out[(i + 1) % k]], v);
      if (d1 < d0 + 1) {
        beta_start[i] = 1;
        ++wraps;
      }
    }
    if (wraps != 1) continue;  // the start breaks the order here
    std::vector<std::pair<int, double>> one;
    for (std::size_t i = 0; i < k; ++i) {
      const int beta = m.add_column(0, 1, 0, true, beta_start[i]);
      one.push_back({beta, 1.0});
      std::vector<std::pair<int, double>> row = {{beta, 8.0}};
      add_out_direction(edges[out[(i + 1) % k]], v, 1.0, row);
      add_out_direction(edges[out[i]], v, -1.0, row);
      m.add_row(std::move(row), 1, 1e30);
    }
    m.add_row(std::move(one), 1, 1);
  }
}

// Planarity for nearby segments (Nöllenburg and Wolff's constraint, restricted to segments
// within 2 l_const of each other in the start, as all pairs would be quadratic): two segments
// without a common node keep one of the separations they have in the start, i.e. one lies
// at least d beyond the other along one of the 8 directions. Only the start's separating
// directions are offered, so a pair keeps its sides. Pairs that touch or cross in the start
// (crossings the geography has) are left free. The result is still checked for crossings.
void add_planarity_rows(const std::vector<XY>& pos, const std::vector<MipEdge>& edges, const OctilinearMip& mip,
                        double l_const, double big, MipModel& m) {
  // Coordinate along direction d: E x, NE x+y, N y, NW y-x, W -x, SW -x-y, S -y, SE x-y.
  constexpr double kCx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
  constexpr double kCy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
  auto along = [&](int d, XY q) { return kCx[d] * q.x + kCy[d] * q.y; };
  const double reach = 2 * l_const, margin = l_const / 4;
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (std::size_t j = i + 1; j < edges.size(); ++j) {
      const auto& s = edges[i];
      const auto& t = edges[j];
      if (s.a == t.a || s.a == t.b || s.b == t.a || s.b == t.b) continue;
      const XY s0 = pos[s.a], s1 = pos[s.b], t0 = pos[t.a], t1 = pos[t.b];
      const double gap_x = std::max(std::min(t0.x, t1.x) - std::max(s0.x, s1.x), std::min(s0.x, s1.x) - std::max(t0.x, t1.x));
      const double gap_y = std::max(std::min(t0.y, t1.y) - std::max(s0.y, s1.y), std::min(s0.y, s1.y) - std::max(t0.y, t1.y));
      if (gap_x > reach || gap_y > reach) continue;
      double separation[8], best = 0;
      for (int d = 0; d < 8; ++d) {  // t beyond s along d
        separation[d] = std::min(along(d, t0), along(d, t1)) - std::max(along(d, s0), along(d, s1));
        best = std::max(best, separation[d]);
      }
      if (best <= 1e-9) continue;  // touching or crossing in the start
      const double need = std::min(margin, best);
      std::vector<int> offered;
      for (int d = 0; d < 8; ++d)
        if (separation[d] >= need) offered.push_back(d);
      std::vector<std::pair<int, double>> any;
      for (int d : offered) {
        const int gamma = offered.size() == 1 ? -1 : m.add_column(0, 1, 0, true, separation[d] >= need ? 1.0 : 0.0);
        if (gamma >= 0) any.push_back({gamma, 1.0});
        for (auto tp : {t.a, t.b})
          for (auto sq : {s.a, s.b}) {
            // along(t end) - along(s end) >= need, relaxed by big when gamma is 0.
            std::vector<std::pair<int, double>> row;
            if (kCx[d] != 0) row.insert(row.end(), {{mip.x[tp], kCx[d]}, {mip.x[sq], -kCx[d]}});
            if (kCy[d] != 0) row.insert(row.end(), {{mip.y[tp], kCy[d]}, {mip.y[sq], -kCy[d]}});
            if (gamma >= 0) {
              row.push_back({gamma, -big});
              m.add_row(std::move(row), need - big, 1e30);
            } else {
              m.add_row(std::move(row), need, 1e30);
            }
          }
      }
      if (!any.empty()) m.add_row(std::move(any), 1, 1e30);
    }
}

}  // namespace

OctilinearMip build_octilinear_mip(const LayoutGraph& g, const Layout& start_in, const MipLayoutParams& p) {
  OctilinearMip mip;
  auto& m = mip.model;
  // Scale the start until every edge is as long as eq. 5.3 asks (scaling keeps it octilinear
  // and planar), so the start is feasible with the full minimum lengths.
  Layout start = start_in;
  double grow = 1.0;
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    double len = 0;
    for (std::size_t i = 1; i < start.paths[e].size(); ++i)
      len += std::hypot(start.paths[e][i].x - start.paths[e][i - 1].x, start.paths[e][i].y - start.paths[e][i - 1].y);
    if (len > 0) grow = std::max(grow, g.min_length[e] / len);
  }
  grow *= 1.001;  // strictly inside
  for (auto& q : start.pos) q = {q.x * grow, q.y * grow};
  for (auto& path : start.paths)
    for (auto& q : path) q = {q.x * grow, q.y * grow};
  std::vector<XY> pos = start.pos;
  std::vector<MipEdge> edges;
  mip.edge_nodes.resize(g.edges.size());
  for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
    const auto& path = start.paths[e];
    auto [u, v] = g.edges[e];
    std::vector<std::uint32_t> nodes{u};
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
      nodes.push_back(static_cast<std::uint32_t>(pos.size()));
      pos.push_back(path[i]);
    }
    nodes.push_back(v);
    mip.edge_nodes[e] = nodes;
    double total = 0;
    for (std::size_t i = 1; i < path.size(); ++i) total += std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
    int geo = sector(g.pos[u], g.pos[v]);
    for (std::size_t i = 1; i < nodes.size(); ++i) {
      double len = std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
      // This segment's share of l_uv (the scaled start has at least that).
      double share = total > 0 ? g.min_length[e] * len / total : 0.0;
      edges.push_back({nodes[i - 1], nodes[i], e, sector(path[i - 1], path[i]), geo, std::min(share, len), {}, len});
    }
  }
  contract_straight_stations(g, pos, edges, mip.placement);

  double x0 = pos[0].x, x1 = pos[0].x, y0 = pos[0].y, y1 = pos[0].y;
  for (const auto& q : pos) {
    x0 = std::min(x0, q.x);
    x1 = std::max(x1, q.x);
    y0 = std::min(y0, q.y);
    y1 = std::max(y1, q.y);
  }
  double extent = std::max({x1 - x0, y1 - y0, 1.0});
  double pad = extent;
  double big = 4 * extent + 100;  // big-M: larger than any coordinate difference

  for (std::uint32_t v = 0; v < pos.size(); ++v) {
    const bool contracted = v < mip.placement.size() && mip.placement[v].on;
    mip.x.push_back(contracted ? -1 : m.add_column(x0 - pad, x1 + pad, 0, false, pos[v].x));
    mip.y.push_back(contracted ? -1 : m.add_column(y0 - pad, y1 + pad, 0, false, pos[v].y));
  }

  const double r2 = 1.0 / std::sqrt(2.0);
  for (auto& e : edges) {
    std::vector<int> allowed = {(e.start_sector + 7) % 8, e.start_sector, (e.start_sector + 1) % 8};
    if (std::find(allowed.begin(), allowed.end(), e.geo_sector) == allowed.end()) allowed.push_back(e.geo_sector);
    std::vector<std::pair<int, double>> one;
    for (int dir : allowed) {
      // cost_topo: leaving the geographic sector costs w_topo (as "1 - alpha_geo"; constants dropped).
      double cost = dir == e.geo_sector ? -p.w_topo : 0.0;
      int col = m.add_column(0, 1, cost, true, dir == e.start_sector ? 1.0 : 0.0);
      e.alpha[dir] = col;
      one.push_back({col, 1.0});
    }
    m.add_row(one, 1, 1);

    auto xa = mip.x[e.a], xb = mip.x[e.b], ya = mip.y[e.a], yb = mip.y[e.b];
    for (int dir : allowed) {
      int a = e.alpha[dir];
      // The perpendicular offset vanishes: |cx*dx + cy*dy| <= M (1 - alpha).
      double cx = 0, cy = 0;  // the combination that must be zero
      double lx = 0, ly = 0;  // the combination that must be >= length
      double need = e.min_length;
      switch (dir) {
        case 0: cy = 1; lx = 1; break;
        case 1: cx = 1; cy = -1; lx = 1; need *= r2; break;
        case 2: cx = 1; ly = 1; break;
        case 3: cx = 1; cy = 1; ly = 1; need *= r2; break;
        case 4: cy = 1; lx = -1; break;
        case 5: cx = 1; cy = -1; lx = -1; need *= r2; break;
        case 6: cx = 1; ly = -1; break;
        case 7: cx = 1; cy = 1; lx = 1; need *= r2; break;
      }
      std::vector<std::pair<int, double>> zero = {{xb, cx}, {xa, -cx}, {yb, cy}, {ya, -cy}, {a, big}};
      m.add_row(zero, -1e30, big);  // cx dx + cy dy + M alpha <= M
      std::vector<std::pair<int, double>> zero_neg = {{xb, -cx}, {xa, cx}, {yb, -cy}, {ya, cy}, {a, big}};
      m.add_row(zero_neg, -1e30, big);
      std::vector<std::pair<int, double>> length = {{xb, lx}, {xa, -lx}, {yb, ly}, {ya, -ly}, {a, -big}};
      m.add_row(length, need - big, 1e30);  // lx dx + ly dy - M alpha >= need - M
    }
    // cost_length: lambda >= |dx|, |dy| (L-infinity), in units of l_const.
    double lam0 = std::max(std::abs(pos[e.b].x - pos[e.a].x), std::abs(pos[e.b].y - pos[e.a].y));
    int lam = m.add_column(0, 1e30, p.w_length / p.l_const, false, lam0);
    for (auto [cxv, cyv] : {std::pair{1.0, 0.0}, std::pair{-1.0, 0.0}, std::pair{0.0, 1.0}, std::pair{0.0, -1.0}})
      m.add_row({{lam, 1}, {mip.x[e.b], -cxv}, {mip.x[e.a], cxv}, {mip.y[e.b], -cyv}, {mip.y[e.a], cyv}}, 0, 1e30);
  }

  // cost_place (not in the paper): u >= |x - x_start|, v >= |y - y_start| for every station
  // that is a MIP node, in units of l_const. Without it the MIP trades any distance from the
  // geography for a bend (with 10 s, Sydney 16 -> 11 bends took its displacement from 2.6 to
  // 4.6 %), because the start's geography enters only through the sectors.
  // A contracted station is at (1 - t) a + t b, linear in its segment's ends: it pays too (or a
  // straight branch of them would swing freely about its ends).
  if (p.w_place > 0)
    for (std::uint32_t v = 0; v < g.pos.size(); ++v) {
      const auto& on = mip.placement[v];
      for (bool is_x : {true, false}) {
        std::vector<std::pair<int, double>> at;  // the station's coordinate as terms
        if (!on.on) at = {{is_x ? mip.x[v] : mip.y[v], 1.0}};
        else at = {{is_x ? mip.x[on.a] : mip.y[on.a], 1.0 - on.t}, {is_x ? mip.x[on.b] : mip.y[on.b], on.t}};
        const double at_start = is_x ? pos[v].x : pos[v].y;
        const int u = m.add_column(0, 1e30, p.w_place / p.l_const, false, 0.0);
        std::vector<std::pair<int, double>> above = {{u, 1.0}}, below = {{u, 1.0}};
        for (auto [col, c] : at) {
          above.push_back({col, -c});
          below.push_back({col, c});
        }
        m.add_row(std::move(above), -at_start, 1e30);  // u >= x - x0
        m.add_row(std::move(below), at_start, 1e30);   // u >= x0 - x
      }
    }

  std::vector<std::vector<std::size_t>> at(pos.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    at[edges[i].a].push_back(i);
    at[edges[i].b].push_back(i);
  }
  add_order_rows(g, pos, edges, at, m);
  add_planarity_rows(pos, edges, mip, p.l_const, 2 * big, m);

  // cost_bend between consecutive segments: at dummy nodes (same edge) and where a line passes
  // a station. Turn = min_k |out - in + 8k|, with direction values sum(i * alpha_i) and +4 for a
  // segment stored against the walking direction.
  auto add_bend = [&](std::size_t in, std::size_t out, std::uint32_t v) {
    const auto& ei = edges[in];
    const auto& eo = edges[out];
    // direction of travel into v along `in`, and out of v along `out`
    double in_offset = ei.b == v ? 0.0 : 4.0;
    double out_offset = eo.a == v ? 0.0 : 4.0;
    int delta = eo.start_sector + static_cast<int>(out_offset) - ei.start_sector - static_cast<int>(in_offset);
    int best_k = 0, best_turn = 99;
    for (int k = -2; k <= 2; ++k)
      if (std::abs(delta + 8 * k) < best_turn) {
        best_turn = std::abs(delta + 8 * k);
        best_k = k;
      }
    int bd = m.add_column(0, 3, p.w_bend, false, best_turn);
    int kk = m.add_column(-2, 2, 0, true, best_k);
    // bd >= +-(out - in + 8k)
    std::vector<std::pair<int, double>> expr;
    for (auto [dir, col] : eo.alpha) expr.push_back({col, static_cast<double>(dir)});
    for (auto [dir, col] : ei.alpha) expr.push_back({col, -static_cast<double>(dir)});
    expr.push_back({kk, 8.0});
    double constant = out_offset - in_offset;
    std::vector<std::pair<int, double>> pos_row = {{bd, 1.0}}, neg_row = {{bd, 1.0}};
    for (auto [c, v2] : expr) {
      pos_row.push_back({c, -v2});
      neg_row.push_back({c, v2});
    }
    m.add_row(pos_row, constant, 1e30);    // bd - expr >= constant
    m.add_row(neg_row, -constant, 1e30);   // bd + expr >= -constant
  };
  for (std::uint32_t v = 0; v < pos.size(); ++v) {
    const auto& inc = at[v];
    if (v >= g.pos.size()) {  // dummy: its two segments
      if (inc.size() == 2) add_bend(inc[0], inc[1], v);
      continue;
    }
    std::map<std::uint32_t, std::vector<std::size_t>> by_line;
    for (auto i : inc)
      for (auto l : g.edge_lines[edges[i].edge]) by_line[l].push_back(i);
    for (const auto& [line, list] : by_line)
      if (list.size() == 2) add_bend(list[0], list[1], v);
  }
  // The start's objective in the model's own terms (constants dropped as above).
  mip.start_objective = 0;
  for (std::size_t c = 0; c < m.columns(); ++c) mip.start_objective += m.cost[c] * m.start[c];
  return mip;
}

Layout decode_octilinear_mip(const OctilinearMip& mip, const std::vector<double>& x, std::size_t nodes) {
  Layout out;
  auto column_at = [&](std::uint32_t v) {
    return XY{x[static_cast<std::size_t>(mip.x[v])], x[static_cast<std::size_t>(mip.y[v])]};
  };
  auto at = [&](std::uint32_t v) {
    if (mip.x[v] >= 0) return column_at(v);
    const auto& p = mip.placement[v];  // contracted: at its share of the segment through it
    const XY a = column_at(p.a), b = column_at(p.b);
    return XY{a.x + p.t * (b.x - a.x), a.y + p.t * (b.y - a.y)};
  };
  for (std::uint32_t v = 0; v < nodes; ++v) out.pos.push_back(at(v));
  for (const auto& list : mip.edge_nodes) {
    std::vector<XY> path;
    for (auto v : list) {
      XY p = at(v);
      if (path.size() >= 2) {
        const auto& a = path[path.size() - 2];
        const auto& b = path.back();
        double cross = (b.x - a.x) * (p.y - b.y) - (b.y - a.y) * (p.x - b.x);
        double dot = (b.x - a.x) * (p.x - b.x) + (b.y - a.y) * (p.y - b.y);
        if (std::abs(cross) < 1e-6 && dot >= 0) path.back() = p;  // straight on: drop the dummy
        else path.push_back(p);
      } else {
        path.push_back(p);
      }
    }
    out.paths.push_back(std::move(path));
  }
  out.method = "mip";
  return out;
}

}  // namespace tourmap::metro
