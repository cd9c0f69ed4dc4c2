#pragma once
// Pose-aware quadric simplification of one cluster (sec. 3.4.3, after Mohr & Gleicher's
// pose-independent simplification): every vertex carries one error quadric per representative
// pose, built from the ORIGINAL mesh's planes around it in that pose; a half-edge collapse u->v
// costs max over poses p of (Q_u^p + Q_v^p)(x_v^p), and Q_v^p += Q_u^p afterwards. The quadrics
// live for the whole hierarchy build, so a parent's errors are measured against the base mesh,
// not against its children's simplified surface.
//
// Half-edge collapses only: the surviving vertex is an original vertex, so no new vertex is made
// and the original skinning data stays valid at every level.

#include "crowd/skinned_model.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace tourmap::crowd {

struct SimplifyResult {
  std::vector<std::uint32_t> indices;  // the simplified triangles (original vertex ids)
  double max_quadric_error = 0;        // max cost of the collapses made (squared model units)
  std::size_t collapses = 0;
  bool reached_target = false;         // false: no legal collapse was left before the target
};

class PoseQuadricSimplifier {
 public:
  // `canonical` from canonical_vertices(model); `poses` are the representative poses (at least one).
  // Initial quadrics: per pose, the plane of every base-mesh triangle is added to its three
  // (welded) vertices, and for every open border edge of the base mesh a plane through the edge,
  // perpendicular to its triangle, is added to both ends so borders keep their shape. Planes
  // have unit normals and unit weight, so a quadric's value is a sum of squared distances
  // (model units^2) and sqrt of it bounds the distance to every plane in it.
  PoseQuadricSimplifier(const SkinnedModel& model, std::vector<std::uint32_t> canonical,
                        const std::vector<const Pose*>& poses);

  // Simplifies the triangles `indices` (original vertex ids, 3 per triangle) to at most
  // `target_triangles` with pose-aware half-edge collapses (OpenMesh's Decimater with a custom
  // module). Vertices for which locked(canonical id) is true are never removed. A collapse is
  // illegal if it flips (or degenerates) a remaining triangle's normal in any pose, or if
  // OpenMesh's topology test rejects it. Triangles OpenMesh cannot represent (welded degenerate
  // or non-manifold ones) are kept as they are and their vertices locked. Corners that survive
  // keep their original vertex id (so seams keep their attributes); a corner moved by a collapse
  // gets the canonical id of the vertex it moved to.
  SimplifyResult simplify(const std::vector<std::uint32_t>& indices, std::size_t target_triangles,
                          const std::function<bool(std::uint32_t)>& locked);

  std::size_t pose_count() const { return poses_; }
  const std::vector<std::uint32_t>& canonical() const { return canonical_; }

 private:
  std::vector<std::uint32_t> canonical_;
  std::size_t poses_ = 0;
  std::vector<Vec3> positions_;   // [v * poses_ + p], skinned, by canonical id
  std::vector<double> quadrics_;  // [(v * poses_ + p) * 10 + k], symmetric 4x4 upper triangle
  std::vector<int> local_of_;     // scratch: canonical id -> vertex of the current cluster mesh
};

}  // namespace tourmap::crowd
