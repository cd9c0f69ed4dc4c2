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

  for (const auto& q : pos) {
    mip.x.push_back(m.add_column(x0 - pad, x1 + pad, 0, false, q.x));
    mip.y.push_back(m.add_column(y0 - pad, y1 + pad, 0, false, q.y));
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

  // cost_bend between consecutive segments: at dummy nodes (same edge) and where a line passes
  // a station. Turn = min_k |out - in + 8k|, with direction values sum(i * alpha_i) and +4 for a
  // segment stored against the walking direction.
  std::vector<std::vector<std::size_t>> at(pos.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    at[edges[i].a].push_back(i);
    at[edges[i].b].push_back(i);
  }
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
  auto at = [&](std::uint32_t v) { return XY{x[static_cast<std::size_t>(mip.x[v])], x[static_cast<std::size_t>(mip.y[v])]}; };
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
