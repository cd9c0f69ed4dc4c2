#pragma once
// Bottom-up construction of the VDR-AM cluster hierarchy (sec. 3.4.3): leaf clusters (error-aware,
// sec. 3.4.2, or the octree baseline, sec. 3.6), merged pairwise into a binary tree, every parent
// holding its children's triangles simplified to half with pose-aware quadrics.
//
// - Pairing: rounds of greedy matching of adjacent clusters (sharing a vertex) by deformation-level
//   difference, disconnected parts by bbox distance (details at pair_up in the .cpp).
// - Simplification (pose_quadric_simplify.hpp): a parent = its children's triangles merged and
//   halved by half-edge collapses; vertices the parent's region shares with the rest of the mesh
//   are locked, so clusters drawn at different levels meet without cracks. A parent that runs out
//   of legal collapses first keeps what it reached (HierarchyStats::clusters_short_of_half).
// - Error (sec. 3.5.1, HierarchyOptions::error_metric): by default half the measured largest
//   distance, over the representative poses, from the original vertices below the cluster to its
//   simplified triangles (cluster_error.hpp); or sqrt of the largest collapse cost (the paper's
//   quadric approximation). Raised to the children's errors so it is monotonic; leaves 0.
//   validate_hierarchy() checks it after every build.
// - Bounds: bbox of the cluster's vertices over every sampled pose of every animation, grown to
//   contain the children's bounds (a parent's vertices are a subset of its children's).
// - Output order: leaves first, then parents in creation order (children before parents; the
//   root is last).

#include "crowd/cluster_hierarchy.hpp"
#include "crowd/leaf_clusters.hpp"

#include <vector>

namespace tourmap::crowd {

// representative_poses[a] = indices into model.animations[a].poses used by the simplification
// (one list per animation; a list may be empty, but not all of them). Bounds use every sampled
// pose regardless. Throws std::invalid_argument on a mismatched list or an index out of range,
// and on an inconsistent model (see require_consistent_mesh). A model without animations is
// simplified in its bind pose (pass an empty list).
ClusterHierarchy build_hierarchy(const SkinnedModel& model, const HierarchyOptions& options,
                                 const std::vector<std::vector<int>>& representative_poses);

// The same over given leaves (each triangle in exactly one leaf), for callers that cluster
// themselves; options.clustering is ignored.
ClusterHierarchy build_hierarchy_from_leaves(const SkinnedModel& model, const HierarchyOptions& options,
                                             const std::vector<std::vector<int>>& representative_poses,
                                             const LeafTriangles& leaves);

// build_hierarchy with the representative poses chosen per animation by select_poses (sec. 3.4.1,
// pose_selection.hpp) with options.pose_distance_fraction and options.mds_dimensions.
ClusterHierarchy build_vdr_hierarchy(const SkinnedModel& model, const HierarchyOptions& options);

}  // namespace tourmap::crowd
