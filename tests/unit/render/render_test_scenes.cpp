#include "render_test_scenes.hpp"

#include "render/egl_context.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <numeric>

namespace tourmap::render::test {
namespace {

crowd::Pose identity_pose(int joints) {
  crowd::Pose p;
  p.skinning.assign(static_cast<std::size_t>(joints), crowd::Affine::Identity());
  p.global = p.skinning;
  return p;
}

// Appends an n x n grid quad face: origin + u * s + v * t for s, t in [0, 1].
void add_face(crowd::SkinnedModel& m, const crowd::Vec3& origin, const crowd::Vec3& u, const crowd::Vec3& v, int n,
              Rgba color) {
  const crowd::Vec3 normal = u.cross(v).normalized();
  const auto first = static_cast<std::uint32_t>(m.positions.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      m.positions.push_back(origin + u * (static_cast<float>(i) / static_cast<float>(n)) +
                            v * (static_cast<float>(j) / static_cast<float>(n)));
      m.normals.push_back(normal);
      m.colors.push_back(color);
      m.joints.push_back({0, 0, 0, 0});
      m.weights.push_back({1, 0, 0, 0});
    }
  const auto at = [&](int i, int j) { return first + static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
}

struct HierarchyBuilder {
  const crowd::SkinnedModel& model;
  crowd::ClusterHierarchy h;
  std::vector<crowd::Vec3> centroid;  // per triangle, bind pose
  float diagonal = 1;

  crowd::Box3 bounds_of(const std::vector<std::uint32_t>& tris) const {
    crowd::Box3 b;
    for (const auto& anim : model.animations)
      for (const auto& pose : anim.poses)
        for (std::uint32_t t : tris)
          for (int k = 0; k < 3; ++k) b.extend(skinned_position(model, pose, model.indices[3 * t + static_cast<std::uint32_t>(k)]));
    return b;
  }

  int add_cluster(const std::vector<std::uint32_t>& tris, int height) {
    crowd::Cluster c;
    c.first_index = static_cast<std::uint32_t>(h.indices.size());
    for (std::uint32_t t : tris)
      for (int k = 0; k < 3; ++k) h.indices.push_back(model.indices[3 * t + static_cast<std::uint32_t>(k)]);
    c.index_count = static_cast<std::uint32_t>(tris.size() * 3);
    c.error = 0.02f * diagonal * static_cast<float>(height);
    c.bounds = bounds_of(tris);
    h.clusters.push_back(c);
    return static_cast<int>(h.clusters.size()) - 1;
  }

  int build(std::vector<std::uint32_t> tris, int levels) {
    if (levels == 0) return add_cluster(tris, 0);
    crowd::Box3 box;
    for (std::uint32_t t : tris) box.extend(centroid[t]);
    int axis = 0;
    box.sizes().maxCoeff(&axis);
    const auto mid = tris.begin() + static_cast<std::ptrdiff_t>(tris.size() / 2);
    std::nth_element(tris.begin(), mid, tris.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return centroid[a][axis] < centroid[b][axis]; });
    const int left = build(std::vector<std::uint32_t>(tris.begin(), mid), levels - 1);
    const int right = build(std::vector<std::uint32_t>(mid, tris.end()), levels - 1);
    std::vector<std::uint32_t> kept;
    for (std::size_t k = 0; k < tris.size(); k += 2) kept.push_back(tris[k]);
    const int id = add_cluster(kept, levels);
    h.clusters[static_cast<std::size_t>(id)].children = {left, right};
    h.clusters[static_cast<std::size_t>(left)].parent = id;
    h.clusters[static_cast<std::size_t>(right)].parent = id;
    return id;
  }

  void set_depth(int id, int depth) {
    auto& c = h.clusters[static_cast<std::size_t>(id)];
    c.depth = depth;
    if (!c.is_leaf())
      for (int child : c.children) set_depth(child, depth + 1);
  }
};

}  // namespace

crowd::SkinnedModel box_model(const crowd::Vec3& half, Rgba color, int n, int poses) {
  crowd::SkinnedModel m;
  m.name = "box";
  const crowd::Vec3 x(2 * half.x(), 0, 0), y(0, 2 * half.y(), 0), z(0, 0, 2 * half.z());
  const crowd::Vec3 lo = -half;
  add_face(m, lo + z, x, y, n, color);          // +z
  add_face(m, lo + x, -x, y, n, color);         // -z (origin at +x, -z corner)
  add_face(m, lo + x, y, z, n, color);          // +x
  add_face(m, lo, z, y, n, color);              // -x
  add_face(m, lo + y, z, x, n, color);          // +y
  add_face(m, lo, x, z, n, color);              // -y
  m.skeleton.joint_names = {"root"};
  m.skeleton.parent = {-1};
  m.skeleton.inverse_bind = {Eigen::Matrix4f::Identity()};
  crowd::Animation a;
  a.name = "still";
  for (int p = 0; p < poses; ++p) a.poses.push_back(identity_pose(1));
  m.animations.push_back(a);
  return m;
}

crowd::SkinnedModel bar_model(Rgba color) {
  crowd::SkinnedModel m;
  m.name = "bar";
  const int segments = 8;
  const float r = 0.1f;
  // Four sides, each a strip along x with its own vertices and normal.
  const crowd::Vec3 corners[4] = {{0, -r, r}, {0, r, r}, {0, r, -r}, {0, -r, -r}};
  for (int side = 0; side < 4; ++side) {
    const crowd::Vec3 a = corners[side], b = corners[(side + 1) % 4];
    const crowd::Vec3 normal = ((a + b) * 0.5f).normalized();
    const auto first = static_cast<std::uint32_t>(m.positions.size());
    for (int s = 0; s <= segments; ++s) {
      const float x = 2.f * static_cast<float>(s) / segments;
      for (const crowd::Vec3& c : {a, b}) {
        m.positions.push_back(c + crowd::Vec3(x, 0, 0));
        m.normals.push_back(normal);
        m.colors.push_back(color);
        if (x < 1) {
          m.joints.push_back({0, 1, 0, 0});
          m.weights.push_back({1, 0, 0, 0});
        } else if (x > 1) {
          m.joints.push_back({1, 0, 0, 0});
          m.weights.push_back({1, 0, 0, 0});
        } else {
          m.joints.push_back({0, 1, 0, 0});
          m.weights.push_back({0.5f, 0.5f, 0, 0});
        }
      }
    }
    for (int s = 0; s < segments; ++s) {
      const std::uint32_t v = first + static_cast<std::uint32_t>(2 * s);
      m.indices.insert(m.indices.end(), {v, v + 2, v + 3, v, v + 3, v + 1});
    }
  }
  m.skeleton.joint_names = {"lower", "upper"};
  m.skeleton.parent = {-1, 0};
  m.skeleton.inverse_bind = {Eigen::Matrix4f::Identity(), Eigen::Matrix4f::Identity()};
  crowd::Animation a;
  a.name = "bend";
  a.poses.push_back(identity_pose(2));
  crowd::Pose bent = identity_pose(2);
  bent.skinning[1] = Eigen::Translation3f(1, 0, 0) * Eigen::AngleAxisf(std::numbers::pi_v<float> / 2, crowd::Vec3::UnitZ()) *
                     Eigen::Translation3f(-1, 0, 0);
  bent.global[1] = bent.skinning[1];
  a.poses.push_back(bent);
  m.animations.push_back(a);
  return m;
}

crowd::Vec3 skinned_position(const crowd::SkinnedModel& model, const crowd::Pose& pose, std::size_t vertex) {
  crowd::Vec3 out = crowd::Vec3::Zero();
  for (int k = 0; k < 4; ++k) {
    const float w = model.weights[vertex][static_cast<std::size_t>(k)];
    if (w > 0) out += w * (pose.skinning[model.joints[vertex][static_cast<std::size_t>(k)]] * model.positions[vertex]);
  }
  return out;
}

crowd::ClusterHierarchy test_hierarchy(const crowd::SkinnedModel& model, int levels) {
  HierarchyBuilder b{model, {}, {}, 1};
  crowd::Box3 all;
  for (const auto& p : model.positions) all.extend(p);
  b.diagonal = all.diagonal().norm();
  const std::size_t tris = model.indices.size() / 3;
  for (std::size_t t = 0; t < tris; ++t)
    b.centroid.push_back((model.positions[model.indices[3 * t]] + model.positions[model.indices[3 * t + 1]] +
                          model.positions[model.indices[3 * t + 2]]) / 3.f);
  std::vector<std::uint32_t> all_tris(tris);
  std::iota(all_tris.begin(), all_tris.end(), 0u);
  b.h.root = b.build(all_tris, levels);
  b.set_depth(b.h.root, 0);
  for (const auto& c : b.h.clusters) {
    ++b.h.stats.clusters;
    if (c.is_leaf()) ++b.h.stats.leaf_clusters;
    b.h.stats.stored_triangles += c.triangle_count();
  }
  b.h.stats.base_triangles = tris;
  return b.h;
}

Rgba pixel(const std::vector<std::uint8_t>& rgba, int width, int height, int x, int y_from_top) {
  const std::size_t at = (static_cast<std::size_t>(height - 1 - y_from_top) * static_cast<std::size_t>(width) +
                          static_cast<std::size_t>(x)) * 4;
  return {rgba[at], rgba[at + 1], rgba[at + 2], rgba[at + 3]};
}

std::array<int, 2> project_to_pixel(const crowd::CameraView& view, const crowd::Vec3& world) {
  const Eigen::Vector4f clip = view.view_proj * world.homogeneous();
  const float x = (clip.x() / clip.w() * 0.5f + 0.5f) * static_cast<float>(view.width);
  const float y = (clip.y() / clip.w() * 0.5f + 0.5f) * static_cast<float>(view.height);
  return {static_cast<int>(std::floor(x)), view.height - 1 - static_cast<int>(std::floor(y))};
}

std::size_t differing_pixels(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int tolerance) {
  if (a.size() != b.size()) return std::max(a.size(), b.size()) / 4;
  std::size_t n = 0;
  for (std::size_t i = 0; i + 3 < a.size(); i += 4)
    for (int k = 0; k < 4; ++k)
      if (std::abs(int{a[i + static_cast<std::size_t>(k)]} - int{b[i + static_cast<std::size_t>(k)]}) > tolerance) {
        ++n;
        break;
      }
  return n;
}

EglContext& shared_context() {
  static EglContext* context = new EglContext();
  context->make_current();
  return *context;
}

}  // namespace tourmap::render::test
