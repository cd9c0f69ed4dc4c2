#include "poi/assignment.hpp"

#include "poi/spatial.hpp"
#include "util/prefault.hpp"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <utility>

// Both solvers are written here: Boost and CGAL have no assignment solver, and Boost.Graph's
// successive_shortest_path_nonnegative_weights runs a full Dijkstra over the whole flow network
// per unit of flow (10^6 of them at 10^6 POIs), where an assignment search can stop at the first
// free column; LEMON's min-cost flow solvers took 15.5 s (cost scaling) and 3.0 s (network
// simplex) on one 138K-point GeoNames round that the shortest paths below solve in 0.2 s. Each
// solver here is a page.

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

// The candidate arcs of every point, with their costs: first the point itself (staying alone,
// at self_loop_penalty), then its k nearest, then the points that have it among theirs. An
// outlier is nobody's near neighbour, yet the optimum would put it into a cycle through its own
// nearest ones (a -> outlier -> b), which needs the arc into it: with the reverse arcs the
// sparse optimum matches the dense one on real data at k = 8 (and merges no 300-point chains).
struct Candidates {
  std::vector<std::uint32_t> first;  // n + 1 offsets into `to` and `cost`
  std::vector<std::uint32_t> to;     // no duplicates; the row's own point first
  std::vector<float> cost;           // float: half the memory traffic of the searches
};

// Per column, what the searches read together (one cache line instead of five arrays).
struct Column {
  double v = 0;                  // potential: reduced costs are c_ij - v_j - u_i
  double d = 0;                  // tentative distance in the search stamped `seen`
  std::uint32_t y = kNone;       // row assigned to this column
  std::uint32_t pred = kNone;    // row the search reached it from
  std::uint32_t seen = 0, done = 0;  // stamps of the last search that reached / settled it
};

// A radix heap (Ahuja, Mehlhorn, Orlin and Tarjan 1990) of columns by tentative distance: a
// Dijkstra search pops non-decreasing keys, and non-negative doubles order like their bit
// patterns, so an item sits in the bucket of the highest bit where its key differs from the
// last popped one and moves down at most 64 times. Pushes append; a pop scans one bucket. The
// searches of the long augmenting paths hold 10^4..10^5 columns: popping a 4-ary heap of that
// size took half of their time. Decrease-key pushes again; the stale entry is skipped on pop.
class RadixHeap {
 public:
  bool empty() const { return size_ == 0; }
  double last() const { return last_key_; }
  void clear() {
    for (auto& b : buckets_) b.clear();
    size_ = 0;
    last_ = 0;
    last_key_ = 0;
  }
  // key >= last(): callers clamp (a reduced cost can round a hair below zero).
  void push(double key, std::uint32_t col) {
    const std::uint64_t k = bits(key);
    buckets_[bucket(k)].push_back({k, col});
    ++size_;
  }
  std::pair<double, std::uint32_t> pop() {
    if (buckets_[0].empty()) {
      std::size_t i = 1;
      while (buckets_[i].empty()) ++i;
      auto& from = buckets_[i];
      std::uint64_t smallest = from[0].first;
      for (const auto& item : from) smallest = std::min(smallest, item.first);
      last_ = smallest;
      std::memcpy(&last_key_, &last_, sizeof last_);
      for (const auto& item : from) buckets_[bucket(item.first)].push_back(item);
      from.clear();
    }
    const auto item = buckets_[0].back();
    buckets_[0].pop_back();
    --size_;
    return {last_key_, item.second};
  }

 private:
  static std::uint64_t bits(double key) {
    std::uint64_t k;
    std::memcpy(&k, &key, sizeof k);
    return k;
  }
  std::size_t bucket(std::uint64_t k) const {
    return k == last_ ? 0 : static_cast<std::size_t>(64 - __builtin_clzll(k ^ last_));
  }
  std::vector<std::pair<std::uint64_t, std::uint32_t>> buckets_[65];
  std::size_t size_ = 0;
  std::uint64_t last_ = 0;
  double last_key_ = 0;
};

struct Row {
  std::uint32_t x = kNone;  // column assigned to this row
  float cost = 0;           // c_{i, x(i)}
};

}  // namespace

struct SparseCoverScratch::Buffers {
  // The kNN search on both cores of the target machine; started for the first large cover only
  // (a thread costs ~0.1 ms, a kNN search over 20,000 points ~5 ms).
  std::optional<util::ForkJoin> pool;
  Neighbours nb;
  std::vector<std::uint32_t> fill_at;
  std::vector<char> reverse;  // per kNN arc j -> i: whether i lacks j, so i gets the arc back
  Candidates g;
  std::vector<Column> col;
  std::vector<Row> row;
  std::vector<std::uint32_t> free_rows, next_free, settled;
  RadixHeap heap;
};

SparseCoverScratch::SparseCoverScratch() : buffers(std::make_unique<Buffers>()) {}
SparseCoverScratch::~SparseCoverScratch() = default;

namespace {

using Buffers = SparseCoverScratch::Buffers;

void build_candidates(const std::vector<geo::XY>& points, std::size_t k, Buffers& b) {
  const std::size_t n = points.size();
  if (n >= 20000 && !b.pool) b.pool.emplace(2);
  k_nearest(points, std::max<std::size_t>(k, 1), b.nb, b.pool ? &*b.pool : nullptr);
  const Neighbours& nb = b.nb;
  auto listed = [&](std::uint32_t i, std::uint32_t j) {  // j among i's k nearest
    const std::uint32_t* row = &nb.index[i * nb.k];
    return std::find(row, row + nb.k, j) != row + nb.k;
  };
  // A reverse arc j -> i (i among j's nearest) is added unless i lists j too.
  Candidates& g = b.g;
  util::assign_prefaulted(g.first, n + 1, 0u);
  std::vector<char>& reverse = b.reverse;
  util::resize_prefaulted(reverse, n * nb.k);
  for (std::uint32_t j = 0; j < n; ++j) {
    g.first[j + 1] += static_cast<std::uint32_t>(1 + nb.k);
    for (std::size_t a = 0; a < nb.k; ++a) {
      const std::uint32_t i = nb.index[j * nb.k + a];
      reverse[j * nb.k + a] = !listed(i, j);
      g.first[i + 1] += reverse[j * nb.k + a];
    }
  }
  for (std::size_t i = 0; i < n; ++i) g.first[i + 1] += g.first[i];
  util::resize_prefaulted(g.to, g.first[n]);
  util::resize_prefaulted(g.cost, g.first[n]);
  // Fill: the own point and the k nearest at the start of each row, the reverse arcs after them.
  std::vector<std::uint32_t>& fill = b.fill_at;
  util::reserve_prefaulted(fill, n);
  fill.assign(g.first.begin(), g.first.end() - 1);
  for (std::uint32_t i = 0; i < n; ++i) {
    g.to[fill[i]++] = i;
    for (std::size_t a = 0; a < nb.k; ++a) g.to[fill[i]++] = nb.index[i * nb.k + a];
  }
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::size_t a = 0; a < nb.k; ++a)
      if (reverse[j * nb.k + a]) g.to[fill[nb.index[j * nb.k + a]]++] = j;
  // Costs; staying alone costs the penalty over the row's farthest candidate and the mean arc.
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double farthest = 0;
    for (std::size_t a = g.first[i] + 1; a < g.first[i + 1]; ++a) {
      const double c = dist(points[i], points[g.to[a]]);
      g.cost[a] = static_cast<float>(c);
      sum += c;
      farthest = std::max(farthest, c);
    }
    g.cost[g.first[i]] = static_cast<float>(farthest);  // for now; the penalty needs the mean
  }
  const double mean = sum / static_cast<double>(g.to.size() - n);
  for (std::size_t i = 0; i < n; ++i) g.cost[g.first[i]] = static_cast<float>(self_loop_penalty(g.cost[g.first[i]], mean));
}

void assign(Buffers& b, std::uint32_t i, std::uint32_t j, float c) {
  b.row[i] = {j, c};
  b.col[j].y = i;
}

// Greedy start (v = 0): each row takes its cheapest column while that is free.
void greedy_start(Buffers& b) {
  const Candidates& g = b.g;
  b.free_rows.clear();
  for (std::uint32_t i = 0; i < b.row.size(); ++i) {
    std::size_t best = g.first[i];
    for (std::size_t a = best + 1; a < g.first[i + 1]; ++a)
      if (g.cost[a] < g.cost[best]) best = a;
    if (b.col[g.to[best]].y == kNone)
      assign(b, i, g.to[best], g.cost[best]);
    else
      b.free_rows.push_back(i);
  }
}

// Jonker and Volgenant's augmenting row reduction (1987), on the candidate arcs: a free row
// takes its cheapest column j1 and lowers v_j1 by the gap to its second cheapest, so j1 stays its
// minimum; the row it evicts continues the chain while that gap was positive. Cheap, local, and
// it leaves far fewer free rows for the shortest-path phase. Two passes as in JV; a chain is cut
// after 8 steps per free row (its last row waits for the next pass or the shortest paths).
void augmenting_row_reduction(Buffers& b) {
  const Candidates& g = b.g;
  for (int pass = 0; pass < 4 && !b.free_rows.empty(); ++pass) {
    b.next_free.clear();
    std::size_t steps = 0;
    const std::size_t cap = 8 * b.free_rows.size();
    for (std::uint32_t i : b.free_rows) {
      for (;;) {
        std::size_t a1 = kNone, a2 = kNone;
        double u1 = kInf, u2 = kInf;
        for (std::size_t a = g.first[i]; a < g.first[i + 1]; ++a) {
          const double h = g.cost[a] - b.col[g.to[a]].v;
          if (h < u2) {
            if (h >= u1) {
              u2 = h;
              a2 = a;
            } else {
              u2 = u1;
              a2 = a1;
              u1 = h;
              a1 = a;
            }
          }
        }
        std::uint32_t j = g.to[a1], evicted = b.col[j].y;
        const bool gap = u1 < u2 && a2 != kNone;
        if (gap) {
          b.col[j].v -= u2 - u1;
        } else if (evicted != kNone && a2 != kNone) {  // a tie: take the other column instead
          a1 = a2;
          j = g.to[a1];
          evicted = b.col[j].y;
        }
        assign(b, i, j, g.cost[a1]);
        if (evicted == kNone) break;
        b.row[evicted].x = kNone;
        if (gap && ++steps < cap) {
          i = evicted;
          continue;
        }
        b.next_free.push_back(evicted);
        break;
      }
    }
    b.free_rows.swap(b.next_free);
  }
}

// Successive shortest augmenting paths (the augmentation step of Jonker-Volgenant): each
// remaining free row augments along a Dijkstra shortest path over reduced costs to a free
// column, and the columns the search settled get their potentials lowered so the invariant
// holds. Exact over the candidates. An epsilon-scaling auction was tried first: same costs,
// but 6x slower on one round over 10^6 synthetic points, and 10x slower on GeoNames with
// per-point epsilons (price wars across cost scales).
//
// The free rows augment in a fixed pseudo-random order: in a spatial sweep the last rows find
// their free columns at the far end of the map, and each search settles a large part of it
// (GeoNames sorted by x: 6x slower). Most searches settle a handful of columns; a few settle
// tens of thousands and shift a chain of hundreds of pairs (a coast of evenly spaced places
// where one more place changes every pairing's parity), and they take most of the time.
void shortest_augmenting_paths(Buffers& b) {
  const Candidates& g = b.g;
  std::mt19937 rng(20240531);
  std::shuffle(b.free_rows.begin(), b.free_rows.end(), rng);

  RadixHeap& heap = b.heap;  // kept allocated across searches
  std::uint32_t search = 0;
  // Relaxes the arcs of row i, reached at distance `base`, whose u_i is `u`.
  // Returns a free column reached at the distance being settled (no shorter path can exist,
  // so the search ends there without popping the other columns of that distance), or kNone.
  auto relax = [&](std::uint32_t i, double base, double u) {
    for (std::size_t a = g.first[i]; a < g.first[i + 1]; ++a) {
      const std::uint32_t j = g.to[a];
      Column& c = b.col[j];
      const double nd = std::max(base + g.cost[a] - c.v - u, heap.last());
      if (c.seen != search || (c.done != search && nd < c.d)) {
        c.seen = search;
        c.d = nd;
        c.pred = i;
        if (c.y == kNone && nd <= heap.last()) return j;
        heap.push(nd, j);
      }
    }
    return kNone;
  };
  auto arc_cost = [&](std::uint32_t i, std::uint32_t j) {
    for (std::size_t a = g.first[i];; ++a)
      if (g.to[a] == j) return g.cost[a];
  };
  for (const std::uint32_t f : b.free_rows) {
    ++search;
    double u = kInf;
    for (std::size_t a = g.first[f]; a < g.first[f + 1]; ++a) u = std::min(u, g.cost[a] - b.col[g.to[a]].v);
    std::uint32_t end = relax(f, 0.0, u);
    double length = 0;
    while (end == kNone && !heap.empty()) {
      const auto [dj, j] = heap.pop();
      Column& c = b.col[j];
      if (c.done == search || dj > c.d) continue;
      c.done = search;
      b.settled.push_back(j);
      if (c.y == kNone) {
        end = j;
        length = dj;
        break;
      }
      end = relax(c.y, dj, b.row[c.y].cost - c.v);
    }
    if (end != kNone && b.col[end].done != search) {  // reached tight while relaxing: settle it
      b.col[end].done = search;
      b.settled.push_back(end);
      length = b.col[end].d;
    }
    // Unreachable: the identity is a perfect matching, so every free row has an augmenting path.
    if (end == kNone) throw std::logic_error("min_cycle_cover_sparse: no augmenting path");
    for (const std::uint32_t j : b.settled) b.col[j].v -= length - b.col[j].d;
    for (std::uint32_t j = end;;) {
      const std::uint32_t i = b.col[j].pred, next = b.row[i].x;
      assign(b, i, j, arc_cost(i, j));
      if (i == f) break;
      j = next;
    }
    b.settled.clear();
    heap.clear();
  }
}

CycleCover cover_in_hilbert_order(const std::vector<geo::XY>& points, std::size_t k, Buffers& b) {
  const std::size_t n = points.size();
  build_candidates(points, k, b);
  util::assign_prefaulted(b.col, n, Column{});
  util::assign_prefaulted(b.row, n, Row{});
  greedy_start(b);
  augmenting_row_reduction(b);
  shortest_augmenting_paths(b);
  CycleCover out;
  out.successor.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = b.row[i].x;
    out.successor[i] = j;
    if (j == i) {
      ++out.self_loops;
      out.cost += b.g.cost[b.g.first[i]];
    } else {
      out.cost += dist(points[i], points[j]);
    }
  }
  return out;
}

}  // namespace

CycleCover min_cycle_cover_sparse(const std::vector<geo::XY>& points, std::size_t k, bool in_hilbert_order,
                                  SparseCoverScratch* scratch) {
  const std::size_t n = points.size();
  if (n < 2) return identity(n);
  SparseCoverScratch own;
  Buffers& b = scratch ? *scratch->buffers : *own.buffers;
  if (in_hilbert_order) return cover_in_hilbert_order(points, k, b);
  const std::vector<std::uint32_t> order = hilbert_order(points);  // rank -> point
  std::vector<geo::XY> sorted(n);
  for (std::size_t r = 0; r < n; ++r) sorted[r] = points[order[r]];
  CycleCover out = cover_in_hilbert_order(sorted, k, b);
  std::vector<std::uint32_t> successor(n);
  for (std::size_t r = 0; r < n; ++r) successor[order[r]] = order[out.successor[r]];
  out.successor = std::move(successor);
  return out;
}

}  // namespace tourmap::poi
