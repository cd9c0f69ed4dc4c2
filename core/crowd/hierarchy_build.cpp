#include "crowd/hierarchy_build.hpp"

#include "crowd/cluster_error.hpp"
#include "crowd/deformation_level.hpp"
#include "crowd/hierarchy_io.hpp"
#include "crowd/mesh_topology.hpp"
#include "crowd/pose_quadric_simplify.hpp"
#include "crowd/pose_selection.hpp"
#include "util/elapsed.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace tourmap::crowd {
namespace {

using util::Clock;
using util::ms_since;

float box_distance(const Box3& a, const Box3& b) {
  const Vec3 gap = (a.min() - b.max()).cwiseMax(b.min() - a.max()).cwiseMax(0.f);
  return gap.norm();
}

// A node of the tree being built. Leaves are nodes 0..L-1; a parent always gets a larger id than
// its children, so increasing id order is a bottom-up order.
struct Node {
  Box3 box;          // bind pose, for bbox distances
  float level = 0;   // deformation level: max over the vertices (sec. 3.4.3)
  std::vector<int> adjacent;
  std::array<int, 2> children{-1, -1};
  int parent = -1;
};

void replace_neighbour(std::vector<int>& list, int a, int b, int parent) {
  list.erase(std::remove_if(list.begin(), list.end(), [&](int n) { return n == a || n == b; }), list.end());
  list.push_back(parent);
}

int merge(std::vector<Node>& nodes, int a, int b) {
  const int p = static_cast<int>(nodes.size());
  Node parent;
  parent.box = nodes[static_cast<std::size_t>(a)].box.merged(nodes[static_cast<std::size_t>(b)].box);
  parent.level = std::max(nodes[static_cast<std::size_t>(a)].level, nodes[static_cast<std::size_t>(b)].level);
  parent.children = {a, b};
  for (int child : {a, b})
    for (int n : nodes[static_cast<std::size_t>(child)].adjacent)
      if (n != a && n != b) parent.adjacent.push_back(n);
  std::sort(parent.adjacent.begin(), parent.adjacent.end());
  parent.adjacent.erase(std::unique(parent.adjacent.begin(), parent.adjacent.end()), parent.adjacent.end());
  for (int n : parent.adjacent) replace_neighbour(nodes[static_cast<std::size_t>(n)].adjacent, a, b, p);
  nodes[static_cast<std::size_t>(a)].parent = p;
  nodes[static_cast<std::size_t>(b)].parent = p;
  nodes.push_back(std::move(parent));
  return p;
}

// Bottom-up pairing (sec. 3.4.3), one round at a time so every cluster merges at most once per
// round (a greedy matching) and the tree stays about log2(L) deep:
//  1. adjacent pairs in increasing order of deformation-level difference are matched greedily;
//     differences within the clustering's similarity rule (<= similar_level * max(levels, eps))
//     count as 0, and ties go to the smaller merged bind-pose bbox, then ids. Without that, the
//     noise in the levels of near-rigid clusters (1e-7) would decide their pairing and build
//     long, thin parents whose locked borders cannot be simplified; compact parents halve better
//     (CesiumMan: 10-20% fewer triangles in far cuts);
//  2. a cluster with no adjacent cluster left (a disconnected part) is matched with the nearest
//     cluster by bbox distance among those still unmatched this round (waiting for a matched
//     nearest one would chain hundreds of parts onto one cluster: zdm2.glb has ~1,000 parts);
//  3. a round without any merge (cannot happen with 1-2, kept as a guard) merges the two nearest.
// Returns the root id.
int pair_up(std::vector<Node>& nodes, float similar_level, float eps) {
  std::vector<int> active(nodes.size());
  for (std::size_t i = 0; i < active.size(); ++i) active[i] = static_cast<int>(i);
  std::vector<int> matched_round;
  int round = 0;
  while (active.size() > 1) {
    ++round;
    matched_round.resize(nodes.size() + active.size(), 0);
    auto is_matched = [&](int n) { return matched_round[static_cast<std::size_t>(n)] == round; };
    std::vector<std::tuple<float, float, int, int>> edges;
    for (int a : active)
      for (int b : nodes[static_cast<std::size_t>(a)].adjacent)
        if (a < b) {
          const Node& na = nodes[static_cast<std::size_t>(a)];
          const Node& nb = nodes[static_cast<std::size_t>(b)];
          float difference = std::abs(na.level - nb.level);
          if (difference <= similar_level * std::max({na.level, nb.level, eps})) difference = 0;
          edges.emplace_back(difference, na.box.merged(nb.box).diagonal().norm(), a, b);
        }
    std::sort(edges.begin(), edges.end());
    std::vector<std::pair<int, int>> pairs;
    auto match = [&](int a, int b) {
      matched_round[static_cast<std::size_t>(a)] = round;
      matched_round[static_cast<std::size_t>(b)] = round;
      pairs.emplace_back(a, b);
    };
    for (const auto& [difference, size, a, b] : edges)
      if (!is_matched(a) && !is_matched(b)) match(a, b);
    for (int a : active) {
      if (is_matched(a) || !nodes[static_cast<std::size_t>(a)].adjacent.empty()) continue;
      int nearest = -1;
      float best = std::numeric_limits<float>::infinity();
      for (int b : active) {
        if (b == a || is_matched(b)) continue;
        const float d = box_distance(nodes[static_cast<std::size_t>(a)].box, nodes[static_cast<std::size_t>(b)].box);
        if (d < best) { best = d; nearest = b; }
      }
      if (nearest >= 0) match(a, nearest);
    }
    if (pairs.empty()) {
      std::pair<int, int> closest{active[0], active[1]};
      float best = std::numeric_limits<float>::infinity();
      for (std::size_t i = 0; i < active.size(); ++i)
        for (std::size_t j = i + 1; j < active.size(); ++j) {
          const float d = box_distance(nodes[static_cast<std::size_t>(active[i])].box,
                                       nodes[static_cast<std::size_t>(active[j])].box);
          if (d < best) { best = d; closest = {active[i], active[j]}; }
        }
      match(closest.first, closest.second);
    }
    std::vector<int> next;
    for (int a : active)
      if (!is_matched(a)) next.push_back(a);
    for (const auto& [a, b] : pairs) next.push_back(merge(nodes, a, b));
    active = std::move(next);
  }
  return active.empty() ? -1 : active[0];
}

std::vector<const Pose*> gather_poses(const SkinnedModel& m, const std::vector<std::vector<int>>& reps,
                                      const Pose& bind_pose) {
  if (reps.size() != m.animations.size())
    throw std::invalid_argument("model '" + m.name + "': " + std::to_string(reps.size()) +
                                " representative pose lists for " + std::to_string(m.animations.size()) +
                                " animations");
  std::vector<const Pose*> poses;
  for (std::size_t a = 0; a < reps.size(); ++a)
    for (int p : reps[a]) {
      if (p < 0 || static_cast<std::size_t>(p) >= m.animations[a].poses.size())
        throw std::invalid_argument("model '" + m.name + "', animation '" + m.animations[a].name +
                                    "': representative pose " + std::to_string(p) + " out of range (" +
                                    std::to_string(m.animations[a].poses.size()) + " poses)");
      const Pose& pose = m.animations[a].poses[static_cast<std::size_t>(p)];
      if (!pose.skinning.empty() && pose.skinning.size() != m.skeleton.parent.size())
        throw std::invalid_argument("model '" + m.name + "', animation '" + m.animations[a].name + "', pose " +
                                    std::to_string(p) + ": skinning matrices do not match the skeleton");
      poses.push_back(&pose);
    }
  if (poses.empty()) {
    if (!m.animations.empty())
      throw std::invalid_argument("model '" + m.name + "': no representative pose in any animation");
    poses.push_back(&bind_pose);  // no animation: the bind pose (empty skinning = identity)
  }
  return poses;
}

void require_partition(const SkinnedModel& m, const LeafTriangles& leaves) {
  std::vector<char> seen(m.triangle_count(), 0);
  for (const auto& leaf : leaves) {
    if (leaf.empty()) throw std::invalid_argument("leaf clusters: an empty leaf");
    for (std::uint32_t t : leaf) {
      if (t >= seen.size() || seen[t])
        throw std::invalid_argument("leaf clusters: triangle " + std::to_string(t) +
                                    (t >= seen.size() ? " out of range" : " in two leaves"));
      seen[t] = 1;
    }
  }
  if (std::find(seen.begin(), seen.end(), 0) != seen.end())
    throw std::invalid_argument("leaf clusters: a triangle is in no leaf");
}

// Leaf nodes (bind-pose box, level = max over vertices) and their adjacency: leaves are adjacent
// when triangles of both share a vertex. Also returns the (vertex, leaf) incidences.
std::vector<Node> leaf_nodes(const SkinnedModel& m, const LeafTriangles& leaves, const std::vector<std::uint32_t>& canonical,
                             const std::vector<float>& levels, std::vector<std::pair<std::uint32_t, int>>& vertex_leaf) {
  const std::size_t L = leaves.size();
  std::vector<Node> nodes(L);
  vertex_leaf.clear();
  vertex_leaf.reserve(3 * m.triangle_count());
  for (std::size_t l = 0; l < L; ++l)
    for (std::uint32_t t : leaves[l])
      for (std::size_t k = 0; k < 3; ++k) {
        const std::uint32_t v = m.indices[3 * t + k];
        nodes[l].box.extend(m.positions[v]);
        nodes[l].level = std::max(nodes[l].level, levels[v]);
        vertex_leaf.emplace_back(canonical[v], static_cast<int>(l));
      }
  std::sort(vertex_leaf.begin(), vertex_leaf.end());
  vertex_leaf.erase(std::unique(vertex_leaf.begin(), vertex_leaf.end()), vertex_leaf.end());
  std::vector<std::pair<int, int>> leaf_pairs;
  for (std::size_t i = 0; i < vertex_leaf.size();) {
    std::size_t j = i;
    while (j < vertex_leaf.size() && vertex_leaf[j].first == vertex_leaf[i].first) ++j;
    for (std::size_t a = i; a < j; ++a)
      for (std::size_t b = a + 1; b < j; ++b) leaf_pairs.emplace_back(vertex_leaf[a].second, vertex_leaf[b].second);
    i = j;
  }
  std::sort(leaf_pairs.begin(), leaf_pairs.end());
  leaf_pairs.erase(std::unique(leaf_pairs.begin(), leaf_pairs.end()), leaf_pairs.end());
  for (const auto& [a, b] : leaf_pairs) {
    nodes[static_cast<std::size_t>(a)].adjacent.push_back(b);
    nodes[static_cast<std::size_t>(b)].adjacent.push_back(a);
  }
  return nodes;
}

// Leaf ranges in depth-first order: a cluster's region is the contiguous range [lo, hi) of leaf
// positions, so "vertex v is only used by triangles of this cluster" becomes a range test on the
// smallest and largest leaf position among v's triangles.
struct LeafRanges {
  std::vector<std::uint32_t> position;  // per leaf
  std::vector<std::uint32_t> lo, hi;    // per node
};

LeafRanges leaf_ranges(const std::vector<Node>& nodes, std::size_t leaf_count, int root) {
  LeafRanges r;
  r.position.resize(leaf_count);
  r.lo.resize(nodes.size());
  r.hi.resize(nodes.size());
  std::uint32_t next = 0;
  std::vector<std::pair<int, bool>> stack{{root, false}};
  while (!stack.empty()) {
    const auto [n, done] = stack.back();
    stack.pop_back();
    const auto i = static_cast<std::size_t>(n);
    const Node& node = nodes[i];
    if (node.children[0] < 0) {
      r.position[i] = next;
      r.lo[i] = next;
      r.hi[i] = ++next;
    } else if (done) {
      r.lo[i] = r.lo[static_cast<std::size_t>(node.children[0])];
      r.hi[i] = r.hi[static_cast<std::size_t>(node.children[1])];
    } else {
      stack.emplace_back(n, true);
      stack.emplace_back(node.children[1], false);
      stack.emplace_back(node.children[0], false);
    }
  }
  return r;
}

// build_hierarchy_from_leaves with the vertex trajectories already computed (`traj_ms` is the
// time they took, counted as clustering).
ClusterHierarchy build_from_leaves(const SkinnedModel& m, const HierarchyOptions& options,
                                   const std::vector<std::vector<int>>& representative_poses,
                                   const LeafTriangles& leaves, const VertexTrajectories& traj, double traj_ms) {
  const auto t_start = Clock::now();
  require_consistent_mesh(m);
  if (m.triangle_count() == 0) throw std::invalid_argument("model '" + m.name + "' has no triangles");
  const Pose bind_pose;
  const std::vector<const Pose*> poses = gather_poses(m, representative_poses, bind_pose);
  require_partition(m, leaves);

  ClusterHierarchy h;
  auto& stats = h.stats;
  stats.base_triangles = m.triangle_count();
  for (const Animation& a : m.animations) stats.poses_per_animation.push_back(a.poses.size());
  for (const auto& r : representative_poses) stats.representative_poses_per_animation.push_back(r.size());

  // Leaf nodes and the tree (clustering time).
  const auto t_cluster = Clock::now();
  stats.clustering_ms = traj_ms;
  const std::vector<std::uint32_t> canonical = canonical_vertices(m);
  const std::size_t L = leaves.size();
  std::vector<std::pair<std::uint32_t, int>> vertex_leaf;  // (canonical vertex, leaf), unique
  std::vector<Node> nodes = leaf_nodes(m, leaves, canonical, traj.deformation_level, vertex_leaf);
  Box3 bind;
  for (const Vec3& p : m.positions) bind.extend(p);
  const int root =
      pair_up(nodes, options.similar_level, ErrorAwareClusterOptions{}.rigid_level_fraction * bind.diagonal().norm());
  stats.clustering_ms += ms_since(t_cluster);

  const auto t_simplify = Clock::now();
  const std::size_t N = nodes.size();
  const LeafRanges ranges = leaf_ranges(nodes, L, root);
  const std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> first_leaf(m.vertex_count(), none), last_leaf(m.vertex_count(), 0);
  for (const auto& [v, l] : vertex_leaf) {
    first_leaf[v] = std::min(first_leaf[v], ranges.position[static_cast<std::size_t>(l)]);
    last_leaf[v] = std::max(last_leaf[v], ranges.position[static_cast<std::size_t>(l)]);
  }

  PoseQuadricSimplifier simplifier(m, canonical, poses);
  std::vector<std::vector<std::uint32_t>> stored(N);
  std::vector<float> error(N, 0.f);
  for (std::size_t l = 0; l < L; ++l)
    for (std::uint32_t t : leaves[l])
      stored[l].insert(stored[l].end(), m.indices.begin() + 3 * t, m.indices.begin() + 3 * t + 3);

  // Measured errors (ClusterError::measured). Distances at or below `resolution` (1e-6 of the
  // bind-pose bbox diagonal, the order of float rounding in skinned positions) need not be exact.
  const bool measured = options.error_metric == ClusterError::measured;
  double error_ms = 0;
  std::optional<HausdorffMeter> meter;
  if (measured) {
    const auto t_error = Clock::now();
    meter.emplace(m, canonical, poses, N, 1e-6f * bind.diagonal().norm());
    for (std::size_t l = 0; l < L; ++l) meter->add_leaf(l, stored[l]);
    error_ms += ms_since(t_error);
  }

  std::vector<std::uint32_t> merged;
  for (std::size_t n = L; n < N; ++n) {
    const auto [a, b] = nodes[n].children;
    merged = stored[static_cast<std::size_t>(a)];
    merged.insert(merged.end(), stored[static_cast<std::size_t>(b)].begin(), stored[static_cast<std::size_t>(b)].end());
    const std::uint32_t lo = ranges.lo[n], hi = ranges.hi[n];
    // Lock the vertices the cluster shares with the rest of the mesh (no cracks between
    // clusters drawn at different levels).
    auto locked = [&](std::uint32_t v) { return first_leaf[v] < lo || last_leaf[v] >= hi; };
    SimplifyResult r = simplifier.simplify(merged, merged.size() / 3 / 2, locked);
    if (!r.reached_target) ++stats.clusters_short_of_half;
    // Error sphere radius (sec. 3.5.1), monotonic up the tree.
    const float children = std::max(error[static_cast<std::size_t>(a)], error[static_cast<std::size_t>(b)]);
    if (measured) {
      // The sphere's diameter is the Hausdorff distance H; only an H above twice the children's
      // radius can raise the radius, so smaller distances need not be exact.
      const auto t_error = Clock::now();
      const float hausdorff = meter->measure_parent(n, {a, b}, r.indices, 2 * children);
      error[n] = std::max(children, 0.5f * hausdorff);
      error_ms += ms_since(t_error);
    } else {
      error[n] = std::max(children, static_cast<float>(std::sqrt(r.max_quadric_error)));
    }
    stored[n] = std::move(r.indices);
  }
  stats.error_ms = error_ms;
  stats.simplification_ms = ms_since(t_simplify) - error_ms;

  // Output: clusters in node order (children before parents).
  h.root = root;
  h.clusters.resize(N);
  std::size_t total_indices = 0;
  for (const auto& s : stored) total_indices += s.size();
  h.indices.reserve(total_indices);
  for (std::size_t n = 0; n < N; ++n) {
    Cluster& c = h.clusters[n];
    c.first_index = static_cast<std::uint32_t>(h.indices.size());
    c.index_count = static_cast<std::uint32_t>(stored[n].size());
    h.indices.insert(h.indices.end(), stored[n].begin(), stored[n].end());
    c.parent = nodes[n].parent;
    c.children = nodes[n].children;
    c.error = error[n];
    c.deformation_level = nodes[n].level;
    // Over all sampled poses; a parent also covers its children's boxes so the hierarchy is a
    // proper bounding volume hierarchy for culling (its simplified vertices are a subset).
    for (std::uint32_t v : stored[n]) c.bounds.extend(traj.bounds[v]);
    if (!c.is_leaf())
      for (int child : c.children) c.bounds.extend(h.clusters[static_cast<std::size_t>(child)].bounds);
  }
  for (std::size_t n = N; n-- > 0;)
    if (h.clusters[n].parent >= 0) h.clusters[n].depth = h.clusters[static_cast<std::size_t>(h.clusters[n].parent)].depth + 1;
  stats.leaf_clusters = L;
  stats.clusters = N;
  stats.stored_triangles = h.indices.size() / 3;
  stats.total_ms = ms_since(t_start) + traj_ms;
  // Tree shape, index ranges and error monotonicity must hold; a failure is a bug here.
  validate_hierarchy(h, m.vertex_count());
  return h;
}

}  // namespace

ClusterHierarchy build_hierarchy_from_leaves(const SkinnedModel& m, const HierarchyOptions& options,
                                             const std::vector<std::vector<int>>& representative_poses,
                                             const LeafTriangles& leaves) {
  const auto t_start = Clock::now();
  require_consistent_mesh(m);
  const VertexTrajectories traj = vertex_trajectories(m);
  return build_from_leaves(m, options, representative_poses, leaves, traj, ms_since(t_start));
}

ClusterHierarchy build_hierarchy(const SkinnedModel& m, const HierarchyOptions& options,
                                 const std::vector<std::vector<int>>& representative_poses) {
  const auto t_start = Clock::now();
  require_consistent_mesh(m);
  if (options.max_leaf_triangles < 1)
    throw std::invalid_argument("max_leaf_triangles must be >= 1, got " + std::to_string(options.max_leaf_triangles));
  const VertexTrajectories traj = vertex_trajectories(m);
  LeafTriangles leaves;
  if (options.clustering == LeafClustering::error_aware) {
    ErrorAwareClusterOptions cluster_options;
    cluster_options.max_leaf_triangles = options.max_leaf_triangles;
    cluster_options.similar_level = options.similar_level;
    cluster_options.min_group_triangles = std::max(1, options.max_leaf_triangles / 4);
    leaves = error_aware_leaf_clusters(m, traj.deformation_level, cluster_options);
  } else {
    leaves = octree_leaf_clusters(m, options.max_leaf_triangles);
  }
  ClusterHierarchy h = build_from_leaves(m, options, representative_poses, leaves, traj, ms_since(t_start));
  h.stats.total_ms = ms_since(t_start);
  return h;
}

ClusterHierarchy build_vdr_hierarchy(const SkinnedModel& m, const HierarchyOptions& options) {
  const auto t_start = Clock::now();
  std::vector<std::vector<int>> representatives;
  for (std::size_t a = 0; a < m.animations.size(); ++a) {
    if (m.animations[a].poses.size() <= 1) {  // nothing to select (a static model's one pose)
      representatives.push_back(m.animations[a].poses.empty() ? std::vector<int>{} : std::vector<int>{0});
      continue;
    }
    representatives.push_back(
        select_poses(m, static_cast<int>(a), options.pose_distance_fraction, options.mds_dimensions).representatives);
  }
  const double selection_ms = ms_since(t_start);
  ClusterHierarchy h = build_hierarchy(m, options, representatives);
  h.stats.pose_selection_ms = selection_ms;
  h.stats.total_ms = ms_since(t_start);
  return h;
}

}  // namespace tourmap::crowd
