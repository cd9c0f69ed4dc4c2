#pragma once
// Runtime LOD selection (sec. 3.5.1) and view-frustum culling for one instance of a model:
// walk the hierarchy from the root; a cluster outside the frustum is culled with its subtree;
// a cluster whose error sphere projects to <= PoE pixels is drawn; otherwise its children are
// visited (a leaf is always drawn).

#include "cluster_hierarchy.hpp"

#include <Eigen/Core>

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
};

// Pixels covered by the diameter of a sphere of radius r at distance `dist` (perspective).
float projected_diameter_px(float radius, float dist, const CameraView& view);

// Appends to `out` the cluster ids of the cut of `h` for an instance placed by `world`
// (model -> world; may scale uniformly). poe <= 0 or a NoLOD cut: pass poe = 0 to get leaves.
void lod_cut(const ClusterHierarchy& h, const Affine& world, const CameraView& view, float poe,
             std::vector<int>& out, CutStats& stats);

}  // namespace tourmap::crowd
