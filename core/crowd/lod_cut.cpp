#include "lod_cut.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tourmap::crowd {
namespace {

// A frustum plane in model space with |normal| kept for the box's reach along it.
struct ModelPlane {
  float n[3], d, abs_n[3];
};

// Signed distance (in plane units) of a box's nearest and farthest points along the plane's normal.
inline float box_far_side(const ModelPlane& p, const float c[3], const float h[3]) {
  return p.n[0] * c[0] + p.n[1] * c[1] + p.n[2] * c[2] + p.d + (p.abs_n[0] * h[0] + p.abs_n[1] * h[1] + p.abs_n[2] * h[2]);
}
inline float box_near_side(const ModelPlane& p, const float c[3], const float h[3]) {
  return p.n[0] * c[0] + p.n[1] * c[1] + p.n[2] * c[2] + p.d - (p.abs_n[0] * h[0] + p.abs_n[1] * h[1] + p.abs_n[2] * h[2]);
}

}  // namespace

float projected_diameter_px(float radius, float dist, const CameraView& view) {
  if (radius <= 0) return 0;
  if (dist <= 0) return std::numeric_limits<float>::infinity();
  // The viewport spans 2 * dist * tan(fov/2) world units vertically at that distance.
  return 2.f * radius * static_cast<float>(view.height) / (2.f * dist * std::tan(view.fov_y_rad * 0.5f));
}

CutFrame make_cut_frame(const CameraView& view, float poe) {
  CutFrame f;
  // The rows of the view-projection matrix give the planes (Gribb & Hartmann).
  const Eigen::Matrix4f& m = view.view_proj;
  const Eigen::Vector4f r0 = m.row(0), r1 = m.row(1), r2 = m.row(2), r3 = m.row(3);
  f.planes = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2};
  f.eye = view.eye;
  f.lod = poe > 0;
  if (f.lod) {
    // sec. 3.5.1: drawn when r H / (d tan(fov/2)) <= PoE, i.e. (r k)^2 <= d^2. Clamped so an
    // absurdly small PoE cannot make 0 * k^2 a NaN (a zero error is always fine enough).
    const double k = static_cast<double>(view.height) / (std::tan(static_cast<double>(view.fov_y_rad) * 0.5) * poe);
    f.k_sq = static_cast<float>(std::min(k * k, static_cast<double>(std::numeric_limits<float>::max())));
  }
  return f;
}

void lod_cut(const CutTree& tree, const Affine& world, const CutFrame& frame, std::vector<int>& out, CutStats& stats) {
  if (tree.nodes.empty()) return;
  // The planes in model space: n.(L p + t) + d = (L^T n).p + (n.t + d).
  const Eigen::Matrix3f lin = world.linear();
  const Vec3 t = world.translation();
  const float hc[3] = {tree.hull_center.x(), tree.hull_center.y(), tree.hull_center.z()};
  const float hh[3] = {tree.hull_half.x(), tree.hull_half.y(), tree.hull_half.z()};
  std::array<ModelPlane, 6> active;
  int active_count = 0;
  for (const Eigen::Vector4f& wp : frame.planes) {
    const Vec3 n = lin.transpose() * wp.head<3>();
    ModelPlane p{{n.x(), n.y(), n.z()}, wp.head<3>().dot(t) + wp.w(), {std::abs(n.x()), std::abs(n.y()), std::abs(n.z())}};
    // The hull bounds every node's box: wholly behind this plane culls the root (so the whole
    // instance); wholly in front means no node can be behind it, so the walk skips this plane.
    if (box_far_side(p, hc, hh) < 0) {
      ++stats.visited;
      ++stats.frustum_culled;
      return;
    }
    if (box_near_side(p, hc, hh) < 0) active[static_cast<std::size_t>(active_count++)] = p;
  }
  const Vec3 eye_v = lin.inverse() * (frame.eye - t);
  const float eye[3] = {eye_v.x(), eye_v.y(), eye_v.z()};
  const float k_sq = frame.k_sq;
  const bool lod = frame.lod;

  const CutNode* nodes = tree.nodes.data();
  const auto n = static_cast<std::uint32_t>(tree.nodes.size());
  std::size_t visited = 0, culled = 0, drawn = 0, triangles = 0;
  // Depth-first without a stack: refine = the next node (the first child); cull or draw = skip
  // the subtree (the walk then reaches the second child, or the parent's next sibling).
  for (std::uint32_t i = 0; i < n;) {
    const CutNode& c = nodes[i];
    ++visited;
    bool outside = false;
    for (int k = 0; k < active_count; ++k) outside |= box_far_side(active[static_cast<std::size_t>(k)], c.center, c.half) < 0;
    if (outside) {
      ++culled;
      i = c.skip;
      continue;
    }
    bool fine;
    if (lod) {
      // Squared distance from the eye to the box (0 inside it).
      const float dx = std::max(std::abs(eye[0] - c.center[0]) - c.half[0], 0.f);
      const float dy = std::max(std::abs(eye[1] - c.center[1]) - c.half[1], 0.f);
      const float dz = std::max(std::abs(eye[2] - c.center[2]) - c.half[2], 0.f);
      fine = c.error_sq * k_sq <= dx * dx + dy * dy + dz * dz;  // a leaf's -1 always passes
    } else {
      fine = c.error_sq < 0;
    }
    if (fine) {
      out.push_back(tree.cluster[i]);
      ++drawn;
      triangles += tree.triangles[i];
      i = c.skip;
    } else {
      ++i;
    }
  }
  stats.visited += visited;
  stats.frustum_culled += culled;
  stats.drawn += drawn;
  stats.triangles += triangles;
}

void lod_cut(const ClusterHierarchy& h, const Affine& world, const CameraView& view, float poe,
             std::vector<int>& out, CutStats& stats) {
  lod_cut(build_cut_tree(h), world, make_cut_frame(view, poe), out, stats);
}

}  // namespace tourmap::crowd
