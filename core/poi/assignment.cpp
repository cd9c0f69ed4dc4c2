#include "poi/assignment.hpp"

#include "poi/spatial.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>

// Both solvers are written here: Boost and CGAL have no assignment solver, and Boost.Graph's
// successive_shortest_path_nonnegative_weights runs a full Dijkstra over the whole flow network
// per unit of flow (10^6 of them at 10^6 POIs), where an assignment search can stop at the first
// free column. Each solver here is a page.

namespace tourmap::poi {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
constexpr double kInf = std::numeric_limits<double>::infinity();

double dist(geo::XY a, geo::XY b) { return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y)); }

CycleCover identity(std::size_t n) {
  CycleCover c;
  c.successor.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) c.successor[i] = i;
  return c;
}

}  // namespace

double self_loop_penalty(double farthest_candidate, double mean_candidate) {
  return 3.0 * farthest_candidate + (mean_candidate > 0 ? mean_candidate : 1.0);
}

// Kuhn-Munkres with row/column potentials (the O(n^3) shortest-augmenting-path form): rows are
// added one at a time, each by a Dijkstra-like search over reduced costs. 1-based internally,
// column 0 is the virtual start.
CycleCover min_cycle_cover_dense(const std::vector<geo::XY>& points) {
  const std::size_t n = points.size();
  if (n < 2) return identity(n);
  std::vector<double> c(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) c[i * n + j] = dist(points[i], points[j]);

  std::vector<double> u(n + 1, 0.0), v(n + 1, 0.0), minv(n + 1);
  std::vector<std::size_t> p(n + 1, 0), way(n + 1, 0);  // p[j]: row matched to column j
  std::vector<char> used(n + 1);
  for (std::size_t i = 1; i <= n; ++i) {
    p[0] = i;
    std::size_t j0 = 0;
    std::fill(minv.begin(), minv.end(), kInf);
    std::fill(used.begin(), used.end(), 0);
    do {
      used[j0] = 1;
      const std::size_t i0 = p[j0];
      const double* row = &c[(i0 - 1) * n];
      double delta = kInf;
      std::size_t j1 = 0;
      for (std::size_t j = 1; j <= n; ++j) {
        if (used[j]) continue;
        if (j != i0) {  // the diagonal is forbidden: infinite cost
          double cur = row[j - 1] - u[i0] - v[j];
          if (cur < minv[j]) {
            minv[j] = cur;
            way[j] = j0;
          }
        }
        if (minv[j] < delta) {
          delta = minv[j];
          j1 = j;
        }
      }
      for (std::size_t j = 0; j <= n; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      std::size_t j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }

  CycleCover out;
  out.successor.resize(n);
  for (std::size_t j = 1; j <= n; ++j) out.successor[p[j] - 1] = static_cast<std::uint32_t>(j - 1);
  for (std::size_t i = 0; i < n; ++i) out.cost += c[i * n + out.successor[i]];
  return out;
}

namespace {

// The candidate arcs of every point: its k nearest, plus the points that have it among theirs.
// An outlier is nobody's near neighbour, yet the optimum would put it into a cycle through its
// own nearest ones (a -> outlier -> b), which needs the arc into it: with the reverse arcs the
// sparse optimum matches the dense one on real data at k = 8 (and merges no 300-point chains).
struct Arcs {
  std::vector<std::uint32_t> first;  // n + 1 offsets into `to`
  std::vector<std::uint32_t> to;     // sorted per point, no duplicates, never the point itself
};

Arcs symmetric_knn(const std::vector<geo::XY>& points, std::size_t k) {
  const std::size_t n = points.size();
  const Neighbours nb = k_nearest(points, std::max<std::size_t>(k, 1));
  Arcs g;
  g.first.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t a = 0; a < nb.k; ++a) {
      ++g.first[i + 1];
      ++g.first[nb.index[i * nb.k + a] + 1];
    }
  for (std::size_t i = 0; i < n; ++i) g.first[i + 1] += g.first[i];
  g.to.resize(g.first[n]);
  std::vector<std::uint32_t> fill(g.first.begin(), g.first.end() - 1);
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::size_t a = 0; a < nb.k; ++a) {
      const std::uint32_t j = nb.index[i * nb.k + a];
      g.to[fill[i]++] = j;
      g.to[fill[j]++] = i;
    }
  // Sort each list and drop the arcs listed twice (in both kNN lists), compacting in place.
  std::size_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto begin = g.to.begin() + g.first[i], end = g.to.begin() + g.first[i + 1];
    std::sort(begin, end);
    g.first[i] = static_cast<std::uint32_t>(out);
    for (auto it = begin; it != end; ++it)
      if (it == begin || *it != *(it - 1)) g.to[out++] = *it;
  }
  g.first[n] = static_cast<std::uint32_t>(out);
  g.to.resize(out);
  g.to.shrink_to_fit();
  return g;
}

// Successive shortest augmenting paths (the Hungarian method on a sparse graph, as in the
// augmentation step of Jonker-Volgenant): rows are points, columns successors; column
// potentials v keep every reduced cost c_ij - v_j - u_i >= 0 with u_i = c_i,x(i) - v_x(i), zero on
// the assigned pairs. A greedy start assigns each row its nearest column when free; each
// remaining row then augments along a Dijkstra shortest path to a free column, and the columns
// the search settled get their potentials lowered so the invariant holds. Exact over the
// candidates. An epsilon-scaling auction was tried first: same costs, but 6x slower on one round
// over 10^6 synthetic points (12.9 s vs 1.9 s, kNN included), and 10x slower on GeoNames with
// per-point epsilons (price wars across cost scales).
//
// The points come in Hilbert order (memory locality) and the free rows augment in a fixed
// pseudo-random order: in a spatial sweep the last rows find their free columns at the far end
// of the map, and each search settles a large part of it (GeoNames sorted by x: 6x slower).
CycleCover cover_in_hilbert_order(const std::vector<geo::XY>& points, std::size_t k) {
  const std::size_t n = points.size();
  const Arcs g = symmetric_knn(points, k);

  std::vector<double> penalty(n, 0.0);
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t a = g.first[i]; a < g.first[i + 1]; ++a) {
      const double d = dist(points[i], points[g.to[a]]);
      sum += d;
      penalty[i] = std::max(penalty[i], d);
    }
  const double mean = sum / static_cast<double>(g.to.size());
  for (double& p : penalty) p = self_loop_penalty(p, mean);
  auto cost = [&](std::uint32_t i, std::uint32_t j) { return i == j ? penalty[i] : dist(points[i], points[j]); };
  // Calls f(j) for each candidate column of row i: itself, then its arcs.
  auto for_columns = [&](std::uint32_t i, auto&& f) {
    f(i);
    for (std::size_t a = g.first[i]; a < g.first[i + 1]; ++a) f(g.to[a]);
  };

  std::vector<double> v(n, 0.0);
  std::vector<std::uint32_t> x(n, kNone), y(n, kNone), free_rows;  // x: row -> column, y: column -> row
  for (std::uint32_t i = 0; i < n; ++i) {
    std::uint32_t best = i;
    for_columns(i, [&](std::uint32_t j) {
      if (cost(i, j) < cost(i, best)) best = j;
    });
    if (y[best] == kNone) {
      x[i] = best;
      y[best] = i;
    } else {
      free_rows.push_back(i);
    }
  }

  std::mt19937 rng(20240531);
  std::shuffle(free_rows.begin(), free_rows.end(), rng);

  std::vector<double> d(n, kInf);
  std::vector<std::uint32_t> pred(n, kNone), touched, settled;
  std::vector<char> done(n, 0);
  using Item = std::pair<double, std::uint32_t>;
  std::vector<Item> heap;  // a min-heap by distance, kept allocated across searches
  const auto later = std::greater<Item>();
  for (const std::uint32_t f : free_rows) {
    // Relaxes the arcs of row i, reached at distance `base`, whose u_i is `u`.
    auto relax = [&](std::uint32_t i, double base, double u) {
      for_columns(i, [&](std::uint32_t j) {
        if (done[j]) return;
        const double nd = base + cost(i, j) - v[j] - u;
        if (nd < d[j]) {
          if (d[j] == kInf) touched.push_back(j);
          d[j] = nd;
          pred[j] = i;
          heap.emplace_back(nd, j);
          std::push_heap(heap.begin(), heap.end(), later);
        }
      });
    };
    double u = kInf;
    for_columns(f, [&](std::uint32_t j) { u = std::min(u, cost(f, j) - v[j]); });
    relax(f, 0.0, u);
    std::uint32_t end = kNone;
    double length = 0;
    while (!heap.empty()) {
      std::pop_heap(heap.begin(), heap.end(), later);
      const auto [dj, j] = heap.back();
      heap.pop_back();
      if (done[j] || dj > d[j]) continue;
      done[j] = 1;
      settled.push_back(j);
      if (y[j] == kNone) {
        end = j;
        length = dj;
        break;
      }
      relax(y[j], dj, cost(y[j], j) - v[j]);
    }
    // Unreachable: the identity is a perfect matching, so every free row has an augmenting path.
    if (end == kNone) throw std::logic_error("min_cycle_cover_sparse: no augmenting path");
    for (const std::uint32_t j : settled) v[j] -= length - d[j];
    for (std::uint32_t j = end;;) {
      const std::uint32_t i = pred[j], next = x[i];
      x[i] = j;
      y[j] = i;
      if (i == f) break;
      j = next;
    }
    for (const std::uint32_t j : touched) {
      d[j] = kInf;
      done[j] = 0;
    }
    touched.clear();
    settled.clear();
    heap.clear();
  }

  CycleCover out;
  out.successor = std::move(x);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (out.successor[i] == i) ++out.self_loops;
    out.cost += cost(i, out.successor[i]);
  }
  return out;
}

}  // namespace

CycleCover min_cycle_cover_sparse(const std::vector<geo::XY>& points, std::size_t k) {
  const std::size_t n = points.size();
  if (n < 2) return identity(n);
  const std::vector<std::uint32_t> order = hilbert_order(points);  // rank -> point
  std::vector<geo::XY> sorted(n);
  for (std::size_t r = 0; r < n; ++r) sorted[r] = points[order[r]];
  CycleCover out = cover_in_hilbert_order(sorted, k);
  std::vector<std::uint32_t> successor(n);
  for (std::size_t r = 0; r < n; ++r) successor[order[r]] = order[out.successor[r]];
  out.successor = std::move(successor);
  return out;
}

}  // namespace tourmap::poi
