#include "metro/prelayout.hpp"

#include "metro/topology_guard.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace tourmap::metro {

namespace {

// Maps the mean geographic edge length to the mean target length.
double length_scale(const LayoutGraph& g) {
  double geo_mean = 0, target_mean = 0;
  for (std::size_t i = 0; i < g.edges.size(); ++i) {
    auto [u, v] = g.edges[i];
    geo_mean += std::hypot(g.pos[v].x - g.pos[u].x, g.pos[v].y - g.pos[u].y);
    target_mean += g.min_length[i];
  }
  return geo_mean > 0 ? target_mean / geo_mean : 1.0;
}

}  // namespace

std::vector<double> stress_lengths(const LayoutGraph& g, double geo_share) {
  const double s = geo_share * length_scale(g);
  std::vector<double> out(g.min_length);
  for (std::size_t i = 0; i < g.edges.size(); ++i) {
    auto [u, v] = g.edges[i];
    out[i] = std::max(out[i], s * std::hypot(g.pos[v].x - g.pos[u].x, g.pos[v].y - g.pos[u].y));
  }
  return out;
}

std::vector<XY> scale_to_lengths(const LayoutGraph& g) {
  const double s = length_scale(g);
  std::vector<XY> out;
  for (const auto& p : g.pos) out.push_back({s * p.x, s * p.y});
  return out;
}

std::vector<XY> stretch_to_lengths(const LayoutGraph& g, double lambda) {
  const auto n = static_cast<Eigen::Index>(g.pos.size());
  if (n == 0) return {};
  const double s = length_scale(g);

  // Normal equations, shared by x and y: (L + lambda I) P = B.
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd bx = Eigen::VectorXd::Zero(n), by = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    t.emplace_back(i, i, lambda);
    bx[i] += lambda * s * g.pos[i].x;
    by[i] += lambda * s * g.pos[i].y;
  }
  for (std::size_t i = 0; i < g.edges.size(); ++i) {
    auto [u, v] = g.edges[i];
    double dx = g.pos[v].x - g.pos[u].x, dy = g.pos[v].y - g.pos[u].y;
    double len = std::hypot(dx, dy);
    if (len == 0) continue;
    double tx = g.min_length[i] * dx / len, ty = g.min_length[i] * dy / len;
    t.emplace_back(u, u, 1.0);
    t.emplace_back(v, v, 1.0);
    t.emplace_back(u, v, -1.0);
    t.emplace_back(v, u, -1.0);
    bx[v] += tx;
    by[v] += ty;
    bx[u] -= tx;
    by[u] -= ty;
  }
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(t.begin(), t.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(m);
  Eigen::VectorXd x = ldlt.solve(bx), y = ldlt.solve(by);
  std::vector<XY> out(g.pos.size());
  for (Eigen::Index i = 0; i < n; ++i) out[i] = {x[i], y[i]};
  return out;
}

namespace {

// All-pairs graph distances over target lengths (Dijkstra from every node); infinity between
// components.
std::vector<std::vector<double>> graph_distances(const LayoutGraph& g) {
  std::size_t n = g.pos.size();
  std::vector<std::vector<std::pair<std::uint32_t, double>>> adj(n);
  for (std::size_t i = 0; i < g.edges.size(); ++i) {
    auto [u, v] = g.edges[i];
    adj[u].push_back({v, g.min_length[i]});
    adj[v].push_back({u, g.min_length[i]});
  }
  std::vector<std::vector<double>> d(n, std::vector<double>(n, std::numeric_limits<double>::infinity()));
  using Item = std::pair<double, std::uint32_t>;
  for (std::uint32_t s = 0; s < n; ++s) {
    auto& dist = d[s];
    std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
    dist[s] = 0;
    open.push({0, s});
    while (!open.empty()) {
      auto [c, u] = open.top();
      open.pop();
      if (c > dist[u]) continue;
      for (auto [v, w] : adj[u])
        if (c + w < dist[v]) {
          dist[v] = c + w;
          open.push({dist[v], v});
        }
    }
  }
  return d;
}

}  // namespace

std::vector<XY> stress_layout(const LayoutGraph& g, const std::vector<XY>& init, const StressOptions& options) {
  std::size_t n = g.pos.size();
  std::vector<XY> x = init;
  if (n < 2) return x;
  auto d = graph_distances(g);
  TopologyGuard guard;
  if (options.keep_topology) guard = make_topology_guard(g, init);
  const double anchor = options.anchor;
  for (int it = 0; it < options.iterations; ++it) {
    for (std::size_t i = 0; i < n; ++i) {
      // Localized SMACOF update of node i with weights 1/d^2, plus the anchor to its start.
      double wsum = 0, nx = 0, ny = 0;
      for (std::size_t j = 0; j < n; ++j) {
        if (i == j || !std::isfinite(d[i][j]) || d[i][j] <= 0) continue;
        double w = 1.0 / (d[i][j] * d[i][j]);
        double dx = x[i].x - x[j].x, dy = x[i].y - x[j].y;
        double dist = std::sqrt(dx * dx + dy * dy);  // not hypot: the inner loop, and hypot is slow
        double f = dist > 1e-12 ? d[i][j] / dist : 0.0;
        nx += w * (x[j].x + f * dx);
        ny += w * (x[j].y + f * dy);
        wsum += w;
      }
      double a = anchor * (wsum > 0 ? wsum : 1.0);
      nx += a * init[i].x;
      ny += a * init[i].y;
      wsum += a;
      const XY want{nx / wsum, ny / wsum};
      if (!options.keep_topology) {
        x[i] = want;
        continue;
      }
      for (double t : {1.0, 0.5, 0.25}) {
        const XY to{x[i].x + t * (want.x - x[i].x), x[i].y + t * (want.y - x[i].y)};
        if (move_keeps_topology(guard, g, x, static_cast<std::uint32_t>(i), to)) {
          x[i] = to;
          break;
        }
      }
    }
  }
  return x;
}

}  // namespace tourmap::metro
