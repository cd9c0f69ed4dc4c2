#include "poi/spatial.hpp"

#include "util/prefault.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <utility>

namespace tourmap::poi {
namespace {

constexpr std::size_t kNodeSize = 16;  // points per leaf box, boxes per inner box
constexpr double kInf = std::numeric_limits<double>::infinity();

// One level of the packed tree, structure of arrays: box b covers the children
// [b * kNodeSize, (b + 1) * kNodeSize) of the level below (points, for level 0).
struct Level {
  std::vector<double> min_x, min_y, max_x, max_y;
  std::size_t size() const { return min_x.size(); }
  void add(double x0, double y0, double x1, double y1) {
    min_x.push_back(x0);
    min_y.push_back(y0);
    max_x.push_back(x1);
    max_y.push_back(y1);
  }
};

std::vector<Level> pack(const std::vector<geo::XY>& p) {
  std::vector<Level> levels(1);
  for (std::size_t first = 0; first < p.size(); first += kNodeSize) {
    double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
    for (std::size_t i = first; i < std::min(p.size(), first + kNodeSize); ++i) {
      x0 = std::min(x0, p[i].x);
      y0 = std::min(y0, p[i].y);
      x1 = std::max(x1, p[i].x);
      y1 = std::max(y1, p[i].y);
    }
    levels[0].add(x0, y0, x1, y1);
  }
  while (levels.back().size() > 1) {
    const Level& below = levels.back();
    Level up;
    for (std::size_t first = 0; first < below.size(); first += kNodeSize) {
      const std::size_t last = std::min(below.size(), first + kNodeSize);
      up.add(*std::min_element(&below.min_x[first], &below.min_x[0] + last),
             *std::min_element(&below.min_y[first], &below.min_y[0] + last),
             *std::max_element(&below.max_x[first], &below.max_x[0] + last),
             *std::max_element(&below.max_y[first], &below.max_y[0] + last));
    }
    levels.push_back(std::move(up));
  }
  return levels;
}

// The k best candidates so far, nearest first (k is small: insertion is cheapest).
struct Nearest {
  std::size_t k = 0, count = 0;
  std::vector<double> d2;
  std::vector<std::uint32_t> index;
  explicit Nearest(std::size_t k_) : k(k_), d2(k_), index(k_) {}
  double bound() const { return count < k ? kInf : d2[k - 1]; }
  void offer(double d, std::uint32_t j) {
    if (count == k && d >= d2[k - 1]) return;
    std::size_t at = count < k ? count++ : k - 1;
    for (; at > 0 && d2[at - 1] > d; --at) {
      d2[at] = d2[at - 1];
      index[at] = index[at - 1];
    }
    d2[at] = d;
    index[at] = j;
  }
};

double squared(double v) { return v * v; }

// Squared distance from (x, y) to box b of `level` (0 inside).
double box_distance2(const Level& level, std::size_t b, double x, double y) {
  const double dx = std::max({level.min_x[b] - x, 0.0, x - level.max_x[b]});
  const double dy = std::max({level.min_y[b] - y, 0.0, y - level.max_y[b]});
  return dx * dx + dy * dy;
}

double box_box_distance2(const Level& level, std::size_t b, const Level& other, std::size_t o) {
  const double dx = std::max({level.min_x[b] - other.max_x[o], 0.0, other.min_x[o] - level.max_x[b]});
  const double dy = std::max({level.min_y[b] - other.max_y[o], 0.0, other.min_y[o] - level.max_y[b]});
  return dx * dx + dy * dy;
}

// The k nearest of the points of one leaf (a run of kNodeSize points) at once: each first takes
// its candidates from its own run (its neighbours along the curve, so the bound starts tight),
// then one walk down the tree collects the other leaves that could hold a nearer point of any
// of them (box-to-box distance under the loosest bound), and each point scans those of them its
// own bound reaches. One walk for 16 queries instead of 16 walks.
struct LeafQuery {
  std::vector<Nearest> best;
  std::vector<std::uint32_t> leaves;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> stack;  // (level, box)
  explicit LeafQuery(std::size_t k) : best(kNodeSize, Nearest(k)) {}
};

// Distances first (a loop the compiler vectorises), then the few offers under the bound.
void scan_leaf(const std::vector<geo::XY>& p, std::size_t leaf, std::uint32_t q, Nearest& best) {
  const double x = p[q].x, y = p[q].y;
  const std::size_t first = leaf * kNodeSize, count = std::min(p.size() - first, kNodeSize);
  const geo::XY* run = p.data() + first;
  double d2[kNodeSize];
  for (std::size_t i = 0; i < count; ++i) d2[i] = squared(run[i].x - x) + squared(run[i].y - y);
  for (std::size_t i = 0; i < count; ++i)
    if (d2[i] < best.bound() && first + i != q) best.offer(d2[i], static_cast<std::uint32_t>(first + i));
}

void query_leaf(const std::vector<geo::XY>& p, const std::vector<Level>& levels, std::size_t own, LeafQuery& w) {
  const std::size_t first = own * kNodeSize, last = std::min(p.size(), first + kNodeSize);
  auto scan_all = [&](std::size_t leaf) {
    double bound = 0;
    for (std::size_t q = first; q < last; ++q) {
      Nearest& best = w.best[q - first];
      scan_leaf(p, leaf, static_cast<std::uint32_t>(q), best);
      bound = std::max(bound, best.bound());
    }
    return bound;
  };
  for (std::size_t q = first; q < last; ++q) w.best[q - first].count = 0;
  double bound = scan_all(own);
  // A short last run, or k >= kNodeSize: widen along the curve until every point has k.
  std::size_t lo = own, hi = own;  // leaves scanned so far
  while (bound == kInf && (lo > 0 || hi + 1 < levels[0].size())) {
    if (lo > 0) bound = scan_all(--lo);
    if (hi + 1 < levels[0].size()) bound = scan_all(++hi);
  }
  w.leaves.clear();
  w.stack.clear();
  w.stack.emplace_back(static_cast<std::uint32_t>(levels.size() - 1), 0);
  while (!w.stack.empty()) {
    const auto [level, box] = w.stack.back();
    w.stack.pop_back();
    if (level == 0) {
      if (box < lo || box > hi) w.leaves.push_back(box);
      continue;
    }
    const Level& below = levels[level - 1];
    const std::size_t c0 = box * kNodeSize, c1 = std::min(below.size(), c0 + kNodeSize);
    for (std::size_t c = c1; c-- > c0;)  // pushed in reverse: popped in curve order
      if (box_box_distance2(below, c, levels[0], own) < bound)
        w.stack.emplace_back(level - 1, static_cast<std::uint32_t>(c));
  }
  for (std::size_t q = first; q < last; ++q) {
    Nearest& best = w.best[q - first];
    for (std::uint32_t leaf : w.leaves)
      if (box_distance2(levels[0], leaf, p[q].x, p[q].y) < best.bound()) scan_leaf(p, leaf, static_cast<std::uint32_t>(q), best);
  }
}

// Hilbert index of cell (x, y) of a 2^16 x 2^16 grid (the classic xy2d: one quadrant per bit).
std::uint32_t hilbert_index(std::uint32_t x, std::uint32_t y) {
  std::uint32_t d = 0;
  for (std::uint32_t s = 1u << 15; s > 0; s >>= 1) {
    const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += s * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = 0xffff - x;
        y = 0xffff - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

}  // namespace

Neighbours k_nearest(const std::vector<geo::XY>& points, std::size_t k) {
  Neighbours out;
  k_nearest(points, k, out);
  return out;
}

void k_nearest(const std::vector<geo::XY>& points, std::size_t k, Neighbours& out, util::ForkJoin* pool) {
  const std::size_t n = points.size();
  out.k = n < 2 ? 0 : std::min(k, n - 1);
  util::resize_prefaulted(out.index, n * out.k);
  if (out.k == 0) return;
  const std::vector<Level> levels = pack(points);
  // Leaves are handed out in chunks; each thread writes the rows of its own leaves.
  constexpr std::size_t kChunk = 64;
  std::atomic<std::size_t> next_chunk{0};
  auto work = [&](int) {
    LeafQuery query(out.k);
    for (;;) {
      const std::size_t first = next_chunk.fetch_add(kChunk, std::memory_order_relaxed);
      if (first >= levels[0].size()) return;
      for (std::size_t leaf = first; leaf < std::min(levels[0].size(), first + kChunk); ++leaf) {
        query_leaf(points, levels, leaf, query);
        for (std::size_t q = leaf * kNodeSize; q < std::min(n, (leaf + 1) * kNodeSize); ++q) {
          const Nearest& best = query.best[q - leaf * kNodeSize];
          std::copy(best.index.begin(), best.index.end(), out.index.begin() + static_cast<std::ptrdiff_t>(q * out.k));
        }
      }
    }
  };
  if (pool && levels[0].size() > 4 * kChunk)
    pool->run(work);
  else
    work(0);
}

std::vector<std::uint32_t> hilbert_order(const std::vector<geo::XY>& points, std::vector<std::uint32_t>* cells) {
  const std::size_t n = points.size();
  double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  for (const geo::XY& p : points) {
    x0 = std::min(x0, p.x);
    y0 = std::min(y0, p.y);
    x1 = std::max(x1, p.x);
    y1 = std::max(y1, p.y);
  }
  // One scale for both axes, so the curve's cells are square on the map.
  const double side = std::max(x1 - x0, y1 - y0);
  const double scale = side > 0 ? 65535.0 / side : 0.0;
  auto cell = [&](double v, double lo) {
    return static_cast<std::uint32_t>(std::clamp((v - lo) * scale, 0.0, 65535.0));
  };
  // Key in the high half, index in the low: an LSD radix sort on the key's four bytes is stable,
  // so points in one cell keep their input order.
  std::vector<std::uint64_t> keys, swap;
  util::resize_prefaulted(keys, n);
  util::resize_prefaulted(swap, n);
  for (std::size_t i = 0; i < n; ++i)
    keys[i] = (static_cast<std::uint64_t>(hilbert_index(cell(points[i].x, x0), cell(points[i].y, y0))) << 32) | i;
  for (int shift = 32; shift < 64; shift += 8) {
    std::array<std::size_t, 257> start{};
    for (std::uint64_t key : keys) ++start[((key >> shift) & 0xff) + 1];
    for (std::size_t b = 0; b < 256; ++b) start[b + 1] += start[b];
    for (std::uint64_t key : keys) swap[start[(key >> shift) & 0xff]++] = key;
    keys.swap(swap);
  }
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(keys[i]);
  if (cells) {
    cells->resize(n);
    for (std::size_t i = 0; i < n; ++i) (*cells)[i] = static_cast<std::uint32_t>(keys[i] >> 32);
  }
  return order;
}

}  // namespace tourmap::poi
