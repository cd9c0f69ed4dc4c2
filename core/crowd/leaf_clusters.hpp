#pragma once
// Leaf clusters of the cluster hierarchy: the base mesh's triangles split into small, spatially
// coherent groups. Two methods, returning the same type:
//  - error-aware clustering (sec. 3.4.2): group adjacent vertices of similar deformation level,
//    then split big groups at the median;
//  - the naive octree baseline the paper compares against (sec. 3.6).

#include "crowd/skinned_model.hpp"

#include <cstdint>
#include <vector>

namespace tourmap::crowd {

// Triangle ids (into SkinnedModel::indices / 3) per leaf; every triangle is in exactly one leaf.
using LeafTriangles = std::vector<std::vector<std::uint32_t>>;

struct ErrorAwareClusterOptions {
  int max_leaf_triangles = 100;      // s: partitioning splits bigger clusters
  float similar_level = 0.10f;       // "within 10%", see error_aware_leaf_clusters
  // Levels below this fraction of the bind-pose bbox diagonal count as equal to it when the 10%
  // tolerance is computed, so near-rigid vertices (levels ~0 plus noise) form one group instead
  // of thousands of one-vertex groups.
  float rigid_level_fraction = 0.01f;
  // Groups with fewer triangles than this are merged into the adjacent group of closest level
  // (see below); 0 disables it (the paper's rule alone). build_hierarchy uses s / 4.
  int min_group_triangles = 25;
};

// Clustering stage (sec. 3.4.2): vertices are seeded in increasing order of level (ties by id);
// a seed grows a group over mesh adjacency (vertices sharing a triangle edge, after welding, see
// mesh_topology.hpp) taking every unassigned vertex v with
//     |level(v) - level(seed)| <= similar_level * max(level(seed), eps),
//     eps = rigid_level_fraction * bind-pose bbox diagonal,
// so levels within 10% of the seed's join it. A triangle belongs to the group of its corner with
// the highest level (ties: lowest vertex id), so the group's level (max over its vertices) is not
// raised by a less deforming neighbour and a deforming joint's triangles stay with the joint.
// Small groups: where levels vary around a limb (the inside and outside of a bending joint) the
// 10% rule alone leaves hundreds of groups of 1-10 triangles. Such clusters are all border: their
// vertices are shared with neighbours and must stay locked, so they (and their parents) can not
// be simplified. So, smallest first, a group with fewer than min_group_triangles triangles joins
// the adjacent group (triangles sharing a vertex) whose level (max over its triangles' owners) is
// closest; groups with no neighbour (small disconnected parts) stay as they are.
// Partitioning stage: a group with more than max_leaf_triangles triangles is split recursively at
// the median triangle centroid (bind pose) along the longest axis of the centroids' bbox.
// `levels` has one entry per vertex (deformation_levels()). Throws std::invalid_argument on
// mismatched sizes or max_leaf_triangles < 1.
LeafTriangles error_aware_leaf_clusters(const SkinnedModel& model, const std::vector<float>& levels,
                                        const ErrorAwareClusterOptions& options = {});

// Octree baseline (sec. 3.6): the bind-pose triangles, by centroid, split recursively into the
// eight children of a cube until a node has <= max_leaf_triangles triangles (empty children are
// dropped). Nodes that cannot be separated spatially (coincident centroids, depth 24) are split
// at the median index instead, so the bound always holds.
LeafTriangles octree_leaf_clusters(const SkinnedModel& model, int max_leaf_triangles = 100);

}  // namespace tourmap::crowd
