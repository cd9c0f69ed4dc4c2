#include "crowd/leaf_clusters.hpp"

#include "crowd/mesh_topology.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>

namespace tourmap::crowd {
namespace {

using Triangles = std::vector<std::uint32_t>;

std::vector<Vec3> triangle_centroids(const SkinnedModel& m) {
  std::vector<Vec3> c(m.triangle_count());
  for (std::size_t t = 0; t < c.size(); ++t)
    c[t] = (m.positions[m.indices[3 * t]] + m.positions[m.indices[3 * t + 1]] + m.positions[m.indices[3 * t + 2]]) / 3.f;
  return c;
}

Box3 centroid_box(const Triangles& tris, const std::vector<Vec3>& centroids) {
  Box3 b;
  for (std::uint32_t t : tris) b.extend(centroids[t]);
  return b;
}

// Splits `tris` at the median centroid along the longest bbox axis until every part has at most
// `s` triangles; the halves shrink by half each time, so the recursion always ends.
void median_partition(Triangles tris, const std::vector<Vec3>& centroids, std::size_t s, LeafTriangles& out) {
  std::vector<Triangles> stack;
  stack.push_back(std::move(tris));
  while (!stack.empty()) {
    Triangles part = std::move(stack.back());
    stack.pop_back();
    if (part.size() <= s) {
      if (!part.empty()) out.push_back(std::move(part));
      continue;
    }
    int axis = 0;
    centroid_box(part, centroids).sizes().maxCoeff(&axis);
    const auto mid = part.begin() + static_cast<std::ptrdiff_t>(part.size() / 2);
    std::nth_element(part.begin(), mid, part.end(), [&](std::uint32_t a, std::uint32_t b) {
      const float ca = centroids[a][axis], cb = centroids[b][axis];
      return ca != cb ? ca < cb : a < b;
    });
    stack.emplace_back(mid, part.end());
    part.resize(part.size() / 2);
    stack.push_back(std::move(part));
  }
}

void require_leaf_size(int s) {
  if (s < 1) throw std::invalid_argument("max_leaf_triangles must be >= 1, got " + std::to_string(s));
}

// Vertex-vertex adjacency over triangle edges (canonical ids), as CSR.
struct Adjacency {
  std::vector<std::uint32_t> offset, neighbour;
};

Adjacency edge_adjacency(const SkinnedModel& m, const std::vector<std::uint32_t>& canon) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(m.indices.size() * 2);
  for (std::size_t t = 0; t < m.triangle_count(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = canon[m.indices[3 * t + k]], b = canon[m.indices[3 * t + (k + 1) % 3]];
      if (a == b) continue;
      edges.emplace_back(a, b);
      edges.emplace_back(b, a);
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  Adjacency adj;
  adj.offset.assign(m.vertex_count() + 1, 0);
  for (const auto& e : edges) ++adj.offset[e.first + 1];
  std::partial_sum(adj.offset.begin(), adj.offset.end(), adj.offset.begin());
  adj.neighbour.resize(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) adj.neighbour[i] = edges[i].second;  // sorted by first
  return adj;
}

// See ErrorAwareClusterOptions::min_group_triangles. `members` holds the triangles per group;
// merged groups are left empty.
void merge_small_groups(const SkinnedModel& m, const std::vector<std::uint32_t>& canon,
                        const std::vector<float>& owner_level, std::vector<Triangles>& members,
                        std::size_t min_triangles) {
  const std::size_t n = members.size();
  std::vector<float> level(n, 0.f);
  std::vector<std::uint32_t> group_of(m.triangle_count());
  for (std::size_t g = 0; g < n; ++g)
    for (std::uint32_t t : members[g]) {
      level[g] = std::max(level[g], owner_level[t]);
      group_of[t] = static_cast<std::uint32_t>(g);
    }
  // Group adjacency: groups whose triangles share a (welded) vertex.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> vertex_group;
  vertex_group.reserve(m.indices.size());
  for (std::size_t i = 0; i < m.indices.size(); ++i) vertex_group.emplace_back(canon[m.indices[i]], group_of[i / 3]);
  std::sort(vertex_group.begin(), vertex_group.end());
  vertex_group.erase(std::unique(vertex_group.begin(), vertex_group.end()), vertex_group.end());
  std::vector<std::vector<std::uint32_t>> adjacent(n);
  for (std::size_t i = 0; i < vertex_group.size();) {
    std::size_t j = i;
    while (j < vertex_group.size() && vertex_group[j].first == vertex_group[i].first) ++j;
    for (std::size_t a = i; a < j; ++a)
      for (std::size_t b = i; b < j; ++b)
        if (a != b) adjacent[vertex_group[a].second].push_back(vertex_group[b].second);
    i = j;
  }
  // Union-find over merged groups; `members`, `level` and `adjacent` live at the root.
  std::vector<std::uint32_t> root(n);
  std::iota(root.begin(), root.end(), 0u);
  auto find = [&](std::uint32_t g) {
    while (root[g] != g) g = root[g] = root[root[g]];
    return g;
  };
  using Entry = std::pair<std::size_t, std::uint32_t>;  // (size, group), smallest first
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (std::uint32_t g = 0; g < n; ++g)
    if (!members[g].empty() && members[g].size() < min_triangles) queue.emplace(members[g].size(), g);
  while (!queue.empty()) {
    const auto [size, g] = queue.top();
    queue.pop();
    if (find(g) != g || members[g].size() != size) continue;  // stale entry
    std::uint32_t best = g;
    float best_difference = std::numeric_limits<float>::infinity();
    for (std::uint32_t a : adjacent[g]) {
      const std::uint32_t r = find(a);
      if (r == g) continue;
      const float d = std::abs(level[r] - level[g]);
      if (d < best_difference || (d == best_difference && r < best)) {
        best_difference = d;
        best = r;
      }
    }
    if (best == g) continue;  // no neighbour: a small disconnected part
    root[g] = best;
    members[best].insert(members[best].end(), members[g].begin(), members[g].end());
    members[g].clear();
    level[best] = std::max(level[best], level[g]);
    adjacent[best].insert(adjacent[best].end(), adjacent[g].begin(), adjacent[g].end());
    adjacent[g].clear();
    if (members[best].size() < min_triangles) queue.emplace(members[best].size(), best);
  }
}

}  // namespace

LeafTriangles error_aware_leaf_clusters(const SkinnedModel& m, const std::vector<float>& levels,
                                        const ErrorAwareClusterOptions& options) {
  require_consistent_mesh(m);
  require_leaf_size(options.max_leaf_triangles);
  if (levels.size() != m.vertex_count())
    throw std::invalid_argument("error_aware_leaf_clusters: " + std::to_string(levels.size()) + " levels for " +
                                std::to_string(m.vertex_count()) + " vertices");
  const std::vector<std::uint32_t> canon = canonical_vertices(m);
  const Adjacency adj = edge_adjacency(m, canon);
  Box3 bind;
  for (const Vec3& p : m.positions) bind.extend(p);
  const float eps = m.positions.empty() ? 0.f : options.rigid_level_fraction * bind.diagonal().norm();

  // Clustering stage: seeds in increasing level order.
  const std::size_t nv = m.vertex_count();
  std::vector<std::uint32_t> seeds;
  for (std::uint32_t v = 0; v < nv; ++v)
    if (canon[v] == v) seeds.push_back(v);
  std::stable_sort(seeds.begin(), seeds.end(), [&](std::uint32_t a, std::uint32_t b) { return levels[a] < levels[b]; });
  constexpr std::uint32_t unassigned = ~0u;
  std::vector<std::uint32_t> group(nv, unassigned);
  std::uint32_t groups = 0;
  std::vector<std::uint32_t> frontier;
  for (std::uint32_t seed : seeds) {
    if (group[seed] != unassigned) continue;
    const float seed_level = levels[seed];
    const float tolerance = options.similar_level * std::max(seed_level, eps);
    group[seed] = groups;
    frontier.assign(1, seed);
    while (!frontier.empty()) {
      const std::uint32_t v = frontier.back();
      frontier.pop_back();
      for (std::uint32_t i = adj.offset[v]; i < adj.offset[v + 1]; ++i) {
        const std::uint32_t w = adj.neighbour[i];
        if (group[w] != unassigned || std::abs(levels[w] - seed_level) > tolerance) continue;
        group[w] = groups;
        frontier.push_back(w);
      }
    }
    ++groups;
  }

  // Each triangle goes to the group of its most deforming corner.
  std::vector<Triangles> members(groups);
  std::vector<float> owner_level(m.triangle_count());
  for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
    std::uint32_t owner = canon[m.indices[3 * t]];
    for (std::size_t k = 1; k < 3; ++k) {
      const std::uint32_t v = canon[m.indices[3 * t + k]];
      if (levels[v] > levels[owner] || (levels[v] == levels[owner] && v < owner)) owner = v;
    }
    members[group[owner]].push_back(t);
    owner_level[t] = levels[owner];
  }

  if (options.min_group_triangles > 0)
    merge_small_groups(m, canon, owner_level, members, static_cast<std::size_t>(options.min_group_triangles));

  // Partitioning stage.
  const std::vector<Vec3> centroids = triangle_centroids(m);
  LeafTriangles leaves;
  for (Triangles& tris : members)
    if (!tris.empty()) median_partition(std::move(tris), centroids, static_cast<std::size_t>(options.max_leaf_triangles), leaves);
  return leaves;
}

LeafTriangles octree_leaf_clusters(const SkinnedModel& m, int max_leaf_triangles) {
  require_consistent_mesh(m);
  require_leaf_size(max_leaf_triangles);
  const std::size_t s = static_cast<std::size_t>(max_leaf_triangles);
  const std::vector<Vec3> centroids = triangle_centroids(m);
  Triangles all(m.triangle_count());
  std::iota(all.begin(), all.end(), 0u);
  LeafTriangles leaves;
  if (all.empty()) return leaves;

  const Box3 box = centroid_box(all, centroids);
  const float half = 0.5f * std::max(box.sizes().maxCoeff(), 1e-12f);
  struct Node {
    Triangles tris;
    Vec3 center;
    float half;
    int depth;
  };
  constexpr int max_depth = 24;
  std::vector<Node> stack;
  stack.push_back({std::move(all), box.center(), half, 0});
  while (!stack.empty()) {
    Node node = std::move(stack.back());
    stack.pop_back();
    if (node.tris.size() <= s) {
      leaves.push_back(std::move(node.tris));
      continue;
    }
    std::array<Triangles, 8> child;
    for (std::uint32_t t : node.tris) {
      const Vec3& c = centroids[t];
      const int octant = (c.x() >= node.center.x() ? 1 : 0) | (c.y() >= node.center.y() ? 2 : 0) |
                         (c.z() >= node.center.z() ? 4 : 0);
      child[static_cast<std::size_t>(octant)].push_back(t);
    }
    if (node.depth >= max_depth) {  // coincident centroids: the cube can not separate them
      median_partition(std::move(node.tris), centroids, s, leaves);
      continue;
    }
    const float h = node.half * 0.5f;
    for (int o = 0; o < 8; ++o) {
      if (child[static_cast<std::size_t>(o)].empty()) continue;
      const Vec3 offset((o & 1) ? h : -h, (o & 2) ? h : -h, (o & 4) ? h : -h);
      stack.push_back({std::move(child[static_cast<std::size_t>(o)]), node.center + offset, h, node.depth + 1});
    }
  }
  return leaves;
}

}  // namespace tourmap::crowd
