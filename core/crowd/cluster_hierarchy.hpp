#pragma once
// The VDR-AM cluster hierarchy of one model (sec. 3.3): a binary tree of clusters, each holding
// a triangle list over the model's original vertices (simplification uses half-edge collapses,
// so no new vertices are made and every cluster keeps the original skinning data). Leaves hold
// the base mesh; a parent holds its two children merged and simplified to half (sec. 3.4.3).

#include "skinned_model.hpp"

#include <cstdint>
#include <vector>

namespace tourmap::crowd {

struct Cluster {
  std::uint32_t first_index = 0;  // into ClusterHierarchy::indices
  std::uint32_t index_count = 0;  // 3 per triangle
  int parent = -1;
  std::array<int, 2> children{-1, -1};  // both -1 for a leaf
  int depth = 0;                  // 0 at the root
  float error = 0;                // error sphere radius (model units, sec. 3.5.1), see
                                  // ClusterError; monotonic: parent.error >= child.error; 0 at leaves
  float deformation_level = 0;    // max over the cluster's vertices (sec. 3.4.2)
  Box3 bounds;                    // over every sampled pose of every animation (model space)

  bool is_leaf() const { return children[0] < 0; }
  std::uint32_t triangle_count() const { return index_count / 3; }
};

enum class LeafClustering { error_aware, octree };

// How a parent's error sphere is sized (sec. 3.5.1). The paper defines the sphere's DIAMETER as
// the maximum Hausdorff distance between the original mesh and the cluster's simplified mesh,
// and approximates it by the square root of the maximum quadric error.
//  - quadric:  radius = sqrt(max collapse cost) (the paper's approximation). On CesiumMan it is
//              6-20x the real distance, so LOD cuts barely simplify.
//  - measured: H = max over representative poses of the largest distance from the cluster's
//              original base-mesh vertices (those of the leaf triangles below it) to its
//              simplified triangles in that pose (one-sided: original -> simplified, vertex
//              samples to the surface); radius = H / 2 (H is the diameter).
// Both are raised to the children's radii, so errors are monotonic up the tree.
enum class ClusterError { quadric, measured };

struct HierarchyOptions {
  LeafClustering clustering = LeafClustering::error_aware;
  int max_leaf_triangles = 100;          // s (sec. 3.4.2)
  float similar_level = 0.10f;           // adjacent vertices merge when levels differ <= 10%
  float pose_distance_fraction = 0.2f;   // d = fraction of the bind-pose bbox diagonal (3.4.1)
  int mds_dimensions = 9;                // pose space reduction (3.4.1)
  ClusterError error_metric = ClusterError::measured;
};

struct HierarchyStats {
  std::size_t leaf_clusters = 0;
  std::size_t clusters = 0;
  std::size_t base_triangles = 0;
  std::size_t stored_triangles = 0;      // over all clusters
  std::size_t clusters_short_of_half = 0;  // parents whose simplification ran out of legal
                                           // collapses (locked borders, flips) before half
  std::vector<std::size_t> poses_per_animation;           // sampled poses
  std::vector<std::size_t> representative_poses_per_animation;
  double pose_selection_ms = 0, clustering_ms = 0, simplification_ms = 0, total_ms = 0;
  double error_ms = 0;  // measuring cluster errors (ClusterError::measured); not serialized
};

struct ClusterHierarchy {
  std::vector<Cluster> clusters;
  int root = -1;
  std::vector<std::uint32_t> indices;    // triangles of every cluster, cluster by cluster
  HierarchyStats stats;
};

}  // namespace tourmap::crowd
