#include "metro/layout_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

namespace tourmap::metro {
namespace {

constexpr double kAngleTolerance = 1.0;  // degrees: octilinearity, bends, piece merging (ANG_TOL)

double py_mod(double x, double m) { return x - m * std::floor(x / m); }  // Python's %

double direction(XY from, XY to) { return std::atan2(to.y - from.y, to.x - from.x) * 180.0 / M_PI; }

// Signed turn from direction a to direction b, degrees in (-180, 180].
double turn(double a, double b) {
  double t = py_mod(b - a + 180.0, 360.0) - 180.0;
  return t == -180.0 ? 180.0 : t;
}

bool is_octilinear(double a) {
  double r = py_mod(a, 45.0);
  return std::min(r, 45.0 - r) <= kAngleTolerance;
}

std::vector<XY> dedupe(const std::vector<XY>& pts) {
  std::vector<XY> out;
  for (const auto& p : pts)
    if (out.empty() || std::hypot(p.x - out.back().x, p.y - out.back().y) > 1e-9) out.push_back(p);
  return out;
}

// The polyline merged into straight pieces (the tool's pieces_idx).
std::vector<XY> pieces(const std::vector<XY>& raw) {
  auto pts = dedupe(raw);
  if (pts.size() < 3) return pts;
  std::vector<XY> out{pts[0]};
  std::size_t start = 0, cur = 1;
  for (std::size_t q = 2; q < pts.size(); ++q) {
    double piece = direction(pts[start], pts[cur]);
    double next = direction(pts[cur], pts[q]);
    double whole = direction(pts[start], pts[q]);
    if (!(std::abs(turn(piece, next)) <= kAngleTolerance && std::abs(turn(piece, whole)) <= kAngleTolerance)) {
      out.push_back(pts[cur]);
      start = cur;
    }
    cur = q;
  }
  out.push_back(pts[cur]);
  return out;
}

double length(const std::vector<XY>& pts) {
  double s = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) s += std::hypot(pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y);
  return s;
}

struct Edge {
  std::uint32_t u, v;
  std::vector<XY> pts;  // from u to v
  bool drawn;           // every member edge runs from its start node to its end node
};

// Junctions of degree 2 contracted into their edges (the tool's contract_deg2).
std::vector<Edge> contract_junctions(const LayoutGraph& g, const std::vector<bool>& is_station, const Layout& L) {
  std::vector<Edge> edges;
  std::vector<std::vector<std::size_t>> incident(g.pos.size());
  auto near = [](XY a, XY b) { return std::hypot(a.x - b.x, a.y - b.y) <= 1e-6 * std::max({1.0, std::abs(a.x), std::abs(a.y)}); };
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    auto [u, v] = g.edges[e];
    const auto& p = L.paths[e];
    bool drawn = p.size() >= 2 && near(p.front(), L.pos[u]) && near(p.back(), L.pos[v]);
    edges.push_back({u, v, dedupe(p), drawn});
    incident[u].push_back(e);
    incident[v].push_back(e);
  }
  std::vector<bool> alive(edges.size(), true);
  for (std::uint32_t n = 0; n < g.pos.size(); ++n) {
    auto& inc = incident[n];
    if (is_station[n] || inc.size() != 2 || inc[0] == inc[1]) continue;
    Edge a = edges[inc[0]], b = edges[inc[1]];
    if (a.u == n) {  // a must end at n
      std::reverse(a.pts.begin(), a.pts.end());
      std::swap(a.u, a.v);
    }
    if (b.v == n) {  // b must start at n
      std::reverse(b.pts.begin(), b.pts.end());
      std::swap(b.u, b.v);
    }
    Edge merged{a.u, b.v, a.pts, a.drawn && b.drawn};
    merged.pts.insert(merged.pts.end(), b.pts.begin() + (b.pts.empty() ? 0 : 1), b.pts.end());
    merged.pts = dedupe(merged.pts);
    std::size_t id = edges.size();
    for (auto old : {inc[0], inc[1]}) {
      alive[old] = false;
      for (auto end : {edges[old].u, edges[old].v})
        if (end != n) std::replace(incident[end].begin(), incident[end].end(), old, id);
    }
    edges.push_back(std::move(merged));
    alive.push_back(true);
    inc.clear();
  }
  std::vector<Edge> out;
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (alive[e]) out.push_back(std::move(edges[e]));
  return out;
}

// RMS residual of the least-squares similarity (complex a, b: w ~ a z + b) over the diagonal
// of the targets' bounding box (the tool's similarity_fit).
double similarity_displacement(const std::vector<XY>& from, const std::vector<XY>& to) {
  const std::size_t n = from.size();
  if (n == 0) return 0;
  using C = std::complex<double>;
  C zm = 0, wm = 0;
  for (std::size_t i = 0; i < n; ++i) {
    zm += C(from[i].x, from[i].y);
    wm += C(to[i].x, to[i].y);
  }
  zm /= static_cast<double>(n);
  wm /= static_cast<double>(n);
  C num = 0;
  double den = 0;
  for (std::size_t i = 0; i < n; ++i) {
    C z = C(from[i].x, from[i].y) - zm, w = C(to[i].x, to[i].y) - wm;
    num += std::conj(z) * w;
    den += std::norm(z);
  }
  C a = num / (den > 0 ? den : 1.0), b = wm - a * zm;
  double sum = 0;
  XY lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}, hi{-lo.x, -lo.y};
  for (std::size_t i = 0; i < n; ++i) {
    sum += std::norm(a * C(from[i].x, from[i].y) + b - C(to[i].x, to[i].y));
    lo = {std::min(lo.x, to[i].x), std::min(lo.y, to[i].y)};
    hi = {std::max(hi.x, to[i].x), std::max(hi.y, to[i].y)};
  }
  double diag = std::hypot(hi.x - lo.x, hi.y - lo.y);
  return std::sqrt(sum / n) / (diag > 0 ? diag : 1.0);
}

}  // namespace

CompareMetrics metro_compare_metrics(const LayoutGraph& g, const std::vector<bool>& is_station, const Layout& L) {
  CompareMetrics m;
  std::vector<XY> layout_st, geo_st;
  for (std::size_t v = 0; v < g.pos.size(); ++v)
    if (is_station[v]) {
      layout_st.push_back(L.pos[v]);
      geo_st.push_back(g.pos[v]);
    }
  m.displacement = similarity_displacement(layout_st, geo_st);

  auto edges = contract_junctions(g, is_station, L);
  m.edges = edges.size();
  std::vector<std::vector<std::size_t>> incident(g.pos.size());
  std::size_t octilinear = 0;
  double min_len = std::numeric_limits<double>::infinity(), sum_len = 0;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    auto& E = edges[e];
    E.pts = pieces(E.pts);
    m.edges_kept += E.drawn;
    incident[E.u].push_back(e);
    incident[E.v].push_back(e);
    for (std::size_t i = 1; i < E.pts.size(); ++i) {
      ++m.pieces;
      octilinear += is_octilinear(direction(E.pts[i - 1], E.pts[i]));
      if (i >= 2 && std::abs(turn(direction(E.pts[i - 2], E.pts[i - 1]), direction(E.pts[i - 1], E.pts[i]))) > kAngleTolerance)
        ++m.interior_bends;
    }
    double len = length(E.pts);
    min_len = std::min(min_len, len);
    sum_len += len;
  }
  m.octilinear_share = m.pieces ? static_cast<double>(octilinear) / m.pieces : 0;
  double mean = edges.empty() ? 0 : sum_len / edges.size();
  m.min_over_mean_edge = mean > 0 ? min_len / mean : 0;

  // Degree-2 stations: the line should pass straight through.
  for (std::uint32_t n = 0; n < g.pos.size(); ++n) {
    const auto& inc = incident[n];
    if (!is_station[n] || inc.size() != 2 || inc[0] == inc[1]) continue;
    const auto& in = edges[inc[0]].pts;
    const auto& out = edges[inc[1]].pts;
    if (in.size() < 2 || out.size() < 2) continue;
    double d_in = edges[inc[0]].v == n ? direction(in[in.size() - 2], in.back()) : direction(in[1], in[0]);
    double d_out = edges[inc[1]].u == n ? direction(out[0], out[1]) : direction(out.back(), out[out.size() - 2]);
    if (std::abs(turn(d_in, d_out)) > kAngleTolerance) ++m.station_bends;
  }
  m.bends = m.interior_bends + m.station_bends;
  return m;
}

}  // namespace tourmap::metro
