#pragma once
// Binary form of a ClusterHierarchy (little-endian, versioned), and the structural checks a
// hierarchy must pass before the renderer may walk it.
//
// Layout (version 1): "TMCH" | u32 version | u32 cluster count | u32 index count | i32 root |
// 10 x f64 stats (leaf_clusters, clusters, base_triangles, stored_triangles,
// clusters_short_of_half, pose_selection_ms, clustering_ms, simplification_ms, total_ms, 0) |
// u32 n + n x u64 poses_per_animation | u32 n + n x u64 representative_poses_per_animation |
// per cluster: u32 first_index, u32 index_count, i32 parent, i32 child0, i32 child1, i32 depth,
// f32 error, f32 deformation_level, 6 x f32 bounds (min xyz, max xyz) | index count x u32.

#include "crowd/cluster_hierarchy.hpp"

#include <string>
#include <string_view>

namespace tourmap::crowd {

std::string serialize_hierarchy(const ClusterHierarchy& h);

// Throws std::runtime_error naming the problem on truncated, oversized or inconsistent input
// (bad magic/version, counts that do not match the size, anything validate_hierarchy rejects).
// With vertex_count > 0 every index must also be below it.
ClusterHierarchy deserialize_hierarchy(std::string_view bytes, std::size_t vertex_count = 0);

// Throws std::runtime_error unless: the root is in range with no parent; every cluster has no
// or two distinct children whose parent link points back; every cluster is reached exactly once
// from the root; depths count from the root; index ranges are inside `indices` and a multiple
// of 3 (and below vertex_count when it is > 0); errors are finite, >= 0, 0 at leaves and
// monotonic (parent >= child); bounds are not NaN.
void validate_hierarchy(const ClusterHierarchy& h, std::size_t vertex_count = 0);

}  // namespace tourmap::crowd
