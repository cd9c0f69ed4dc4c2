#pragma once
// The measured error of a simplified cluster (sec. 3.5.1, ClusterError::measured): the paper
// sizes each cluster's error sphere by the maximum Hausdorff distance between the original mesh
// and the cluster's simplified mesh (the sphere's diameter), approximated there by sqrt of the
// max quadric error; this measures the distance instead, in every representative pose.
//
// One-sided estimate, original -> simplified, from point samples of the original surface: its
// vertices and its triangles' centroids (on CesiumMan, centroids raise the final errors by 1-3%
// on average over vertices alone, up to 2.5x on a few clusters of tiny error; edge midpoints
// would add another 1-3% for 1.5x more queries). The
// distance from the simplified surface back to the original is not measured: simplification
// only collapses edges onto original vertices, so the simplified surface's corners lie on the
// original surface.

#include "crowd/skinned_model.hpp"
#include "crowd/triangle_bvh.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace tourmap::crowd {

// result[p][v] = vertex v skinned by *poses[p] (eq. 3.1). A model without skin arrays, or a pose
// without matrices (the bind pose of a model without animations), stays in its bind pose.
std::vector<std::vector<Vec3>> posed_positions(const SkinnedModel& model, const std::vector<const Pose*>& poses);

// The largest, over every pose p, of the distances from the samples (posed[p][v] for v in
// `sample_vertices`, and the centroid of every triangle of `sample_triangles`, 3 vertex ids
// each) to the triangles `simplified` (3 vertex ids each) posed by posed[p].
// Distances at or below `known` are not needed exactly (the caller keeps the larger of the
// result and `known`): with H the true maximum, the result R satisfies H <= R <= max(H, known),
// which lets most samples stop at the first triangle within reach (BVH, triangle_bvh.hpp).
// 0 without samples. `bvh` is scratch, reused between calls. Throws std::invalid_argument on
// samples without triangles, a vertex id out of range, or poses of different sizes.
float max_distance_to_simplified(const std::vector<std::vector<Vec3>>& posed,
                                 const std::vector<std::uint32_t>& simplified,
                                 const std::vector<std::uint32_t>& sample_vertices,
                                 const std::vector<std::uint32_t>& sample_triangles, float known, TriangleBvh& bvh);

// Measured errors of a hierarchy built bottom-up: remembers, per node, the original vertices
// (canonical ids, each once) and triangles below it; a parent takes over its children's lists,
// so the lists alive at any time hold the base mesh about once.
class HausdorffMeter {
 public:
  // `canonical` from canonical_vertices(model); `poses` the representative poses; distances at
  // or below `resolution` need not be exact (see max_distance_to_simplified).
  HausdorffMeter(const SkinnedModel& model, const std::vector<std::uint32_t>& canonical,
                 const std::vector<const Pose*>& poses, std::size_t node_count, float resolution);

  // A leaf node with its original triangles (vertex ids, 3 each).
  void add_leaf(std::size_t node, const std::vector<std::uint32_t>& triangles);

  // The Hausdorff estimate H of a parent whose children were added before (as leaves or
  // parents) and whose simplified triangles are `simplified`: exact when it exceeds `known`
  // (e.g. twice the children's error radius, below which it cannot raise the parent's).
  float measure_parent(std::size_t node, const std::array<int, 2>& children,
                       const std::vector<std::uint32_t>& simplified, float known);

 private:
  std::vector<std::uint32_t> canonical_;
  std::vector<std::vector<Vec3>> posed_;
  float resolution_;
  std::vector<std::vector<std::uint32_t>> vertices_, triangles_;  // per node, below it
  std::vector<std::uint32_t> listed_by_, kept_by_;                // per canonical vertex: last node
  std::vector<std::uint32_t> removed_;                             // scratch
  TriangleBvh bvh_;
};

}  // namespace tourmap::crowd
