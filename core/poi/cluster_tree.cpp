#include "poi/cluster_tree.hpp"

#include "poi/assignment.hpp"
#include "poi/spatial.hpp"
#include "util/prefault.hpp"
#include "util/stop.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>

namespace tourmap::poi {
namespace {

// Appends the cluster of `members` (node ids), filling its fields bottom-up from theirs.
std::uint32_t make_node(ClusterTree& t, std::span<const std::uint32_t> members, std::uint32_t level) {
  const std::uint32_t id = static_cast<std::uint32_t>(t.nodes.size());
  ClusterNode c = t.nodes[members[0]];
  c.level = level;
  c.parent = -1;
  c.first_child = static_cast<std::uint32_t>(t.children.size());
  c.child_count = static_cast<std::uint32_t>(members.size());
  double sx = 0, sy = 0;
  c.size = 0;
  for (std::uint32_t m : members) {
    ClusterNode& child = t.nodes[m];
    child.parent = static_cast<std::int32_t>(id);
    t.children.push_back(m);
    sx += child.center.x * child.size;
    sy += child.center.y * child.size;
    c.size += child.size;
    c.min = {std::min(c.min.x, child.min.x), std::min(c.min.y, child.min.y)};
    c.max = {std::max(c.max.x, child.max.x), std::max(c.max.y, child.max.y)};
    if (std::tie(child.worth, c.representative) > std::tie(c.worth, child.representative)) {
      c.worth = child.worth;
      c.representative = child.representative;
    }
  }
  // Centroid of the POIs: children weighted by size; clamped into the bbox against rounding.
  c.center = {std::clamp(sx / c.size, c.min.x, c.max.x), std::clamp(sy / c.size, c.min.y, c.max.y)};
  t.nodes.push_back(c);
  return id;
}

// Step (b): merges each cycle of the cover over `clusters` into one node; self-loops carry over.
void merge_cycles(ClusterTree& t, const std::vector<std::uint32_t>& clusters,
                  const std::vector<std::uint32_t>& successor, std::uint32_t level, std::vector<std::uint32_t>& next) {
  std::vector<char> seen(clusters.size(), 0);
  std::vector<std::uint32_t> members;
  for (std::size_t start = 0; start < clusters.size(); ++start) {
    if (seen[start]) continue;
    members.clear();
    for (std::size_t i = start; !seen[i]; i = successor[i]) {
      seen[i] = 1;
      members.push_back(clusters[i]);
    }
    next.push_back(members.size() == 1 ? members[0] : make_node(t, members, level));
  }
}

// Groups of more than k clusters with identical centres would see only each other's first k in
// the kNN graph and mostly stay alone: such a group merges outright (its cycle cost is 0 anyway).
// `clusters` come in Hilbert order with their curve `cells`; identical centres share a cell, so
// only a run of more than k clusters in one cell can hold such a group. The other clusters go to
// `pending`, still in curve order.
void merge_identical(ClusterTree& t, std::vector<std::uint32_t>& clusters, const std::vector<std::uint32_t>& cells,
                     std::size_t k, std::uint32_t level, std::vector<std::uint32_t>& next,
                     std::vector<std::uint32_t>& pending) {
  auto same = [&](std::uint32_t a, std::uint32_t b) {
    return t.nodes[a].center.x == t.nodes[b].center.x && t.nodes[a].center.y == t.nodes[b].center.y;
  };
  for (std::size_t r0 = 0, r1; r0 < clusters.size(); r0 = r1) {
    for (r1 = r0 + 1; r1 < clusters.size() && cells[r1] == cells[r0];) ++r1;
    const auto run = std::span(clusters).subspan(r0, r1 - r0);
    if (run.size() <= k) {
      pending.insert(pending.end(), run.begin(), run.end());
      continue;
    }
    std::sort(run.begin(), run.end(), [&](std::uint32_t a, std::uint32_t b) {
      const geo::XY p = t.nodes[a].center, q = t.nodes[b].center;
      return std::tie(p.x, p.y, a) < std::tie(q.x, q.y, b);
    });
    for (std::size_t a = 0, b; a < run.size(); a = b) {
      for (b = a + 1; b < run.size() && same(run[a], run[b]);) ++b;
      if (b - a > k) {
        next.push_back(make_node(t, run.subspan(a, b - a), level));
      } else {
        pending.insert(pending.end(), run.begin() + static_cast<std::ptrdiff_t>(a),
                       run.begin() + static_cast<std::ptrdiff_t>(b));
      }
    }
  }
}

// The clusters of `clusters` in Hilbert order of their centres, with their curve cells.
void sort_along_curve(const ClusterTree& t, std::vector<std::uint32_t>& clusters, std::vector<geo::XY>& centers,
                      std::vector<std::uint32_t>& cells) {
  centers.resize(clusters.size());
  for (std::size_t i = 0; i < clusters.size(); ++i) centers[i] = t.nodes[clusters[i]].center;
  const std::vector<std::uint32_t> order = hilbert_order(centers, &cells);
  std::vector<std::uint32_t> sorted(clusters.size());
  for (std::size_t r = 0; r < order.size(); ++r) sorted[r] = clusters[order[r]];
  clusters.swap(sorted);
}

// Progress guarantee for a round that merged nothing: pair clusters with their nearest
// neighbour, closest pairs first (the closest pair overall always merges).
void merge_nearest_pairs(ClusterTree& t, const std::vector<std::uint32_t>& clusters,
                         const std::vector<geo::XY>& centers, std::uint32_t level, std::vector<std::uint32_t>& next) {
  const Neighbours nb = k_nearest(centers, 1);
  std::vector<std::tuple<double, std::uint32_t, std::uint32_t>> pairs;
  for (std::uint32_t i = 0; i < clusters.size(); ++i) {
    const geo::XY a = centers[i], b = centers[nb.index[i]];
    pairs.emplace_back((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y), i, nb.index[i]);
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<char> taken(clusters.size(), 0);
  for (const auto& [d, i, j] : pairs) {
    if (taken[i] || taken[j]) continue;
    taken[i] = taken[j] = 1;
    const std::uint32_t members[2] = {clusters[i], clusters[j]};
    next.push_back(make_node(t, members, level));
  }
  for (std::uint32_t i = 0; i < clusters.size(); ++i)
    if (!taken[i]) next.push_back(clusters[i]);
}

}  // namespace

ClusterTree build_cluster_tree(const std::vector<ClusterPoint>& points, const ClusterOptions& options) {
  ClusterTree t;
  const std::size_t n = points.size();
  if (n > 0x7fffffff) throw std::length_error("build_cluster_tree: too many points for 32-bit node ids");
  t.leaves = n;
  // At most n - 1 clusters (each merges two or more): reserving that avoids a reallocation copy,
  // and faulting its pages in at once saves a kernel trap per 4 KiB (see util/prefault.hpp).
  util::reserve_prefaulted(t.nodes, 2 * n);
  util::reserve_prefaulted(t.children, 2 * n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const ClusterPoint& p = points[i];
    if (!std::isfinite(p.pos.x) || !std::isfinite(p.pos.y) || !std::isfinite(p.worth) || p.worth < 0)
      throw std::invalid_argument("build_cluster_tree: point " + std::to_string(i) +
                                  " needs a finite position and a finite worth >= 0");
    ClusterNode leaf;
    leaf.center = leaf.min = leaf.max = points[i].pos;
    leaf.size = 1;
    leaf.worth = points[i].worth;
    leaf.representative = i;
    t.nodes.push_back(leaf);
  }
  if (n == 0) return t;

  std::vector<std::uint32_t> current(n), next, pending, cells;
  for (std::uint32_t i = 0; i < n; ++i) current[i] = i;
  std::vector<geo::XY> centers;
  SparseCoverScratch scratch;  // the sparse rounds reuse its memory
  // Step (c): one round per level until one root remains; every round merges at least one pair.
  for (std::uint32_t level = 1; current.size() > 1; ++level) {
    util::check_stop();  // a round over a million clusters takes a while
    next.clear();
    pending.clear();
    const bool sparse = current.size() > options.dense_limit;
    if (sparse) {
      sort_along_curve(t, current, centers, cells);
      merge_identical(t, current, cells, std::max<std::size_t>(options.k, 1), level, next, pending);
    } else {
      pending = current;
    }

    if (pending.size() >= 2) {
      centers.resize(pending.size());
      for (std::size_t i = 0; i < pending.size(); ++i) centers[i] = t.nodes[pending[i]].center;
      const CycleCover cover = sparse ? min_cycle_cover_sparse(centers, options.k, true, &scratch)
                                      : min_cycle_cover_dense(centers);
      const std::size_t before = next.size();
      merge_cycles(t, pending, cover.successor, level, next);
      if (next.size() - before == pending.size() && next.size() == current.size()) {
        next.resize(before);
        merge_nearest_pairs(t, pending, centers, level, next);
      }
    } else {
      next.insert(next.end(), pending.begin(), pending.end());
    }
    current.swap(next);
  }
  t.root = current[0];
  return t;
}

}  // namespace tourmap::poi
