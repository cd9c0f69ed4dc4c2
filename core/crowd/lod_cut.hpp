#pragma once
// Runtime LOD selection (sec. 3.5.1) and view-frustum culling for one instance of a model:
// walk the hierarchy from the root; a cluster outside the frustum is culled with its subtree;
// a cluster whose error sphere projects to <= PoE pixels is drawn; otherwise its children are
// visited (a leaf is always drawn).
//
// The rule is evaluated in the instance's model space, where the cluster boxes live: the six
// frustum planes and the eye are moved into model space once per instance, so a cluster is culled
// when its (oriented) box lies wholly behind one plane, and its distance is the eye's distance
// to that box. The instance transform must be rigid with a uniform scale s (as placements are):
// then a world distance is s times the model distance and the error radius also scales by s, so
// the projected-size test  2 (e s) H / (2 (d s) tan(fov/2)) <= PoE  loses s and becomes
// e^2 k^2 <= d^2 with k = H / (tan(fov/2) PoE), a constant of the frame.

#include "cluster_hierarchy.hpp"
#include "cut_tree.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace tourmap::crowd {

struct CameraView {
  Eigen::Matrix4f view_proj = Eigen::Matrix4f::Identity();  // clip = view_proj * world
  Vec3 eye = Vec3::Zero();
  int width = 1280, height = 720;
  float fov_y_rad = 1.0471976f;     // 60 degrees
  float near_m = 0.1f, far_m = 1000.f;
};

struct CutStats {
  std::size_t visited = 0;
  std::size_t drawn = 0;            // clusters appended
  std::size_t frustum_culled = 0;   // subtrees culled (counted once per culled cluster)
  std::size_t triangles = 0;        // of the appended clusters

  CutStats& operator+=(const CutStats& o) {
    visited += o.visited;
    drawn += o.drawn;
    frustum_culled += o.frustum_culled;
    triangles += o.triangles;
    return *this;
  }
};

// Pixels covered by the diameter of a sphere of radius r at distance `dist` (perspective).
float projected_diameter_px(float radius, float dist, const CameraView& view);

// What a frame's cuts share: the world-space frustum planes (a x + b y + c z + d >= 0 inside),
// the eye and k^2 of the projected-size test. poe <= 0 asks for the NoLOD cut (leaves only).
struct CutFrame {
  std::array<Eigen::Vector4f, 6> planes;
  Vec3 eye = Vec3::Zero();
  float k_sq = 0;
  bool lod = false;
};
CutFrame make_cut_frame(const CameraView& view, float poe);

// Appends to `out` the cluster ids of the cut of `tree` for an instance placed by `world`
// (model -> world, rigid with uniform scale), in depth-first order (first child first).
void lod_cut(const CutTree& tree, const Affine& world, const CutFrame& frame, std::vector<int>& out, CutStats& stats);

// The same for a hierarchy, building its cut tree on the spot (O(clusters) per call: for tests
// and offline tools; the renderer keeps a CutTree per model).
void lod_cut(const ClusterHierarchy& h, const Affine& world, const CameraView& view, float poe,
             std::vector<int>& out, CutStats& stats);

}  // namespace tourmap::crowd
