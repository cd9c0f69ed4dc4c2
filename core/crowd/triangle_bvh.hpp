#pragma once
// Point-to-triangle distances for the measured cluster error (sec. 3.5.1, cluster_error.hpp):
// an exact point-triangle distance and a small bounding volume hierarchy over one triangle set
// with a thresholded nearest-triangle query.
//
// Why our own instead of CGAL's AABB_tree: the hierarchy build rebuilds a tree over ~100
// triangles for every cluster and every representative pose (thousands of tiny trees) from
// float positions, and the query it needs is "the distance to the nearest triangle, but stop as
// soon as any triangle is within `enough`" (most queries end at the first triangle tested).
// A median-split BVH over float positions does both in ~100 lines without converting every
// pose to CGAL points.

#include "crowd/skinned_model.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace tourmap::crowd {

// Squared distance from p to the closest point of triangle abc (Ericson, Real-Time Collision
// Detection 5.1.5), computed in double. Degenerate triangles (collinear or coincident corners)
// are handled as their edges.
float point_triangle_distance_sq(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

class TriangleBvh {
 public:
  // (Re)builds over the triangles `indices` (3 vertex ids each) at `positions` (by vertex id);
  // the corners are copied, so `positions` may change afterwards. Buffers are reused between
  // builds. Throws std::invalid_argument on an index count not a multiple of 3 or an id out of
  // range.
  void build(const std::vector<Vec3>& positions, const std::vector<std::uint32_t>& indices);

  // Distance from q to the nearest triangle, exact when it is larger than `enough`; otherwise
  // the search may stop at the first triangle found within `enough` and return that triangle's
  // distance (then true distance <= result <= enough). +infinity without triangles.
  // `hint` (optional, in/out): a triangle slot tried first, set to the slot of the triangle the
  // result came from; queries along a surface pass the previous one (usually within `enough`).
  float distance(const Vec3& q, float enough = 0, std::uint32_t* hint = nullptr) const;

  std::size_t triangle_count() const { return corners_.size(); }

 private:
  struct Node {
    Box3 box;
    std::uint32_t first = 0;  // leaf: first triangle in leaf_triangles_; inner: right child (left = this + 1)
    std::uint32_t count = 0;  // triangles in a leaf, 0 for an inner node
  };
  // A triangle with the edge vectors and products every query needs (double, as
  // point_triangle_distance_sq), so a query costs two dot products before the region tests.
  struct Prepared {
    Eigen::Vector3d a, ab, ac, normal;
    double ab_ab = 0, ac_ac = 0, ab_ac = 0, normal_sq = 0;
    bool degenerate = false;
    Prepared() = default;
    explicit Prepared(const std::array<Vec3, 3>& corners);
    double distance_sq(const Eigen::Vector3d& p) const;
  };
  std::uint32_t build_node(std::uint32_t first, std::uint32_t count);

  std::vector<std::array<Vec3, 3>> corners_;  // input order (build scratch)
  std::vector<Vec3> centroids_;               // build scratch, parallel to corners_
  std::vector<std::uint32_t> order_;          // build scratch: triangle order of the leaves
  std::vector<Prepared> leaf_triangles_;      // corners_ in leaf order, prepared
  std::vector<Node> nodes_;                   // depth-first order, root at 0
};

}  // namespace tourmap::crowd
