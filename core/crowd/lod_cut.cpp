#include "lod_cut.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace tourmap::crowd {
namespace {

// The six frustum planes (a, b, c, d with a*x + b*y + c*z + d >= 0 inside), taken from the rows
// of the view-projection matrix (Gribb & Hartmann).
std::array<Eigen::Vector4f, 6> frustum_planes(const Eigen::Matrix4f& m) {
  const Eigen::Vector4f r0 = m.row(0), r1 = m.row(1), r2 = m.row(2), r3 = m.row(3);
  return {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2};
}

// A box transformed by an affine map, as a world-space AABB (centre/extent form, Arvo 1990).
struct WorldBox {
  Vec3 center, extent;
};

WorldBox to_world(const Box3& box, const Affine& world) {
  const Vec3 c = box.center();
  const Vec3 e = box.sizes() * 0.5f;
  return {world * c, world.linear().cwiseAbs() * e};
}

bool outside_frustum(const WorldBox& b, const std::array<Eigen::Vector4f, 6>& planes) {
  for (const auto& p : planes) {
    const float reach = std::abs(p.x()) * b.extent.x() + std::abs(p.y()) * b.extent.y() +
                        std::abs(p.z()) * b.extent.z();
    if (p.head<3>().dot(b.center) + p.w() + reach < 0) return true;  // wholly behind this plane
  }
  return false;
}

float distance_to_box(const Vec3& eye, const WorldBox& b) {
  const Vec3 d = ((eye - b.center).cwiseAbs() - b.extent).cwiseMax(0.f);
  return d.norm();
}

struct CutWalk {
  const ClusterHierarchy& h;
  const Affine& world;
  const CameraView& view;
  float poe;
  float scale;  // uniform scale of `world`: errors are in model units
  std::array<Eigen::Vector4f, 6> planes;
  std::vector<int>& out;
  CutStats& stats;

  void visit(int id) {
    const Cluster& c = h.clusters[static_cast<std::size_t>(id)];
    ++stats.visited;
    const WorldBox box = to_world(c.bounds, world);
    if (outside_frustum(box, planes)) {
      ++stats.frustum_culled;
      return;
    }
    const bool fine_enough =
        c.is_leaf() || (poe > 0 && projected_diameter_px(c.error * scale, distance_to_box(view.eye, box), view) <= poe);
    if (fine_enough) {
      out.push_back(id);
      ++stats.drawn;
      stats.triangles += c.triangle_count();
      return;
    }
    visit(c.children[0]);
    visit(c.children[1]);
  }
};

}  // namespace

float projected_diameter_px(float radius, float dist, const CameraView& view) {
  if (radius <= 0) return 0;
  if (dist <= 0) return std::numeric_limits<float>::infinity();
  // The viewport spans 2 * dist * tan(fov/2) world units vertically at that distance.
  return 2.f * radius * static_cast<float>(view.height) / (2.f * dist * std::tan(view.fov_y_rad * 0.5f));
}

void lod_cut(const ClusterHierarchy& h, const Affine& world, const CameraView& view, float poe,
             std::vector<int>& out, CutStats& stats) {
  if (h.root < 0) return;
  const float scale = world.linear().col(0).norm();
  CutWalk walk{h, world, view, poe, scale, frustum_planes(view.view_proj), out, stats};
  walk.visit(h.root);
}

}  // namespace tourmap::crowd
