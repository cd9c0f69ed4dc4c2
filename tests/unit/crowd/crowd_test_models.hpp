#pragma once
// Small synthetic models for the hierarchy tests (header only, shared by several test files):
// a two-bone "arm" (a tube, or a flat strip) that bends at an elbow at x = 1, and a static grid.

#include "crowd/lod_cut.hpp"
#include "crowd/skinned_model.hpp"
#include "render/camera.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tourmap::crowd::test_models {

enum class ArmShape { tube, strip };

struct ArmSpec {
  ArmShape shape = ArmShape::tube;
  int rings = 41;         // along x in [0, 2]; ring (rings-1)/2 is at the elbow x = 1
  int around = 16;        // tube: vertices per ring; strip: vertices across (z in [-0.2, 0.2])
  float radius = 0.2f;
  int poses = 20;         // elbow angle 0..90 degrees
  bool root_motion = true;  // the whole arm also translates and turns (levels must ignore it)
};

inline float smoothstep(float a, float b, float x) {
  const float t = std::clamp((x - a) / (b - a), 0.f, 1.f);
  return t * t * (3 - 2 * t);
}

// Bone 0 (upper arm, root) at the origin, bone 1 (forearm) at x = 1, bending about +z.
// Weights blend from bone 0 to bone 1 over x in [0.7, 1.3].
inline SkinnedModel make_arm(const ArmSpec& spec = {}) {
  SkinnedModel m;
  m.name = spec.shape == ArmShape::tube ? "arm" : "strip";
  const bool tube = spec.shape == ArmShape::tube;
  for (int i = 0; i < spec.rings; ++i) {
    const float x = 2.f * static_cast<float>(i) / static_cast<float>(spec.rings - 1);
    for (int j = 0; j < spec.around; ++j) {
      Vec3 p;
      if (tube) {
        const float phi = 2.f * std::numbers::pi_v<float> * static_cast<float>(j) / static_cast<float>(spec.around);
        p = Vec3(x, spec.radius * std::cos(phi), spec.radius * std::sin(phi));
      } else {
        p = Vec3(x, 0.f, -spec.radius + 2.f * spec.radius * static_cast<float>(j) / static_cast<float>(spec.around - 1));
      }
      m.positions.push_back(p);
      m.normals.push_back(tube ? Vec3(0, p.y(), p.z()).normalized() : Vec3(0, 1, 0));
      m.colors.push_back({200, 200, 200, 255});
      const float w1 = smoothstep(0.7f, 1.3f, x);
      m.joints.push_back({0, 1, 0, 0});
      m.weights.push_back({1 - w1, w1, 0, 0});
    }
  }
  const int cols = tube ? spec.around : spec.around - 1;
  for (int i = 0; i + 1 < spec.rings; ++i)
    for (int j = 0; j < cols; ++j) {
      const auto a = static_cast<std::uint32_t>(i * spec.around + j);
      const auto b = static_cast<std::uint32_t>(i * spec.around + (j + 1) % spec.around);
      const auto c = static_cast<std::uint32_t>((i + 1) * spec.around + j);
      const auto d = static_cast<std::uint32_t>((i + 1) * spec.around + (j + 1) % spec.around);
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
  m.skeleton.joint_names = {"upper", "fore"};
  m.skeleton.parent = {-1, 0};
  const Affine inv_bind1(Eigen::Translation3f(-1, 0, 0));
  m.skeleton.inverse_bind = {Eigen::Matrix4f::Identity(), inv_bind1.matrix()};
  Animation anim;
  anim.name = "bend";
  anim.fps = 10;
  anim.duration_s = static_cast<float>(spec.poses - 1) / anim.fps;
  for (int k = 0; k < spec.poses; ++k) {
    const float s = spec.poses > 1 ? static_cast<float>(k) / static_cast<float>(spec.poses - 1) : 0.f;
    const float theta = 0.5f * std::numbers::pi_v<float> * s;
    Affine g0 = Affine::Identity();
    if (spec.root_motion) g0 = Eigen::Translation3f(0.3f * s, 0.1f * s, 0) * Eigen::AngleAxisf(0.4f * s, Vec3::UnitY());
    const Affine g1 = g0 * Eigen::Translation3f(1, 0, 0) * Eigen::AngleAxisf(theta, Vec3::UnitZ());
    Pose pose;
    pose.global = {g0, g1};
    pose.skinning = {g0, g1 * inv_bind1};
    anim.poses.push_back(pose);
  }
  m.animations.push_back(anim);
  return m;
}

// A flat n x n grid in the xz plane, one identity joint and one identity pose (is_static()).
inline SkinnedModel make_static_grid(int n = 30, float size = 3.f) {
  SkinnedModel m;
  m.name = "grid";
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      m.positions.emplace_back(size * static_cast<float>(i) / static_cast<float>(n), 0.f,
                               size * static_cast<float>(j) / static_cast<float>(n));
      m.normals.emplace_back(0, 1, 0);
      m.colors.push_back({128, 128, 128, 255});
      m.joints.push_back({0, 0, 0, 0});
      m.weights.push_back({1, 0, 0, 0});
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const auto a = static_cast<std::uint32_t>(i * (n + 1) + j), b = a + 1;
      const auto c = a + static_cast<std::uint32_t>(n + 1), d = c + 1;
      m.indices.insert(m.indices.end(), {a, b, c, b, d, c});
    }
  m.skeleton.joint_names = {"root"};
  m.skeleton.parent = {-1};
  m.skeleton.inverse_bind = {Eigen::Matrix4f::Identity()};
  Animation still;
  still.name = "static";
  Pose pose;
  pose.skinning = {Affine::Identity()};
  pose.global = {Affine::Identity()};
  still.poses.push_back(pose);
  m.animations.push_back(still);
  return m;
}

// Every representative pose list = all poses.
inline std::vector<std::vector<int>> all_poses(const SkinnedModel& m) {
  std::vector<std::vector<int>> reps;
  for (const Animation& a : m.animations) {
    reps.emplace_back();
    for (std::size_t p = 0; p < a.poses.size(); ++p) reps.back().push_back(static_cast<int>(p));
  }
  return reps;
}

// A perspective camera looking from `eye` at `target` (+Y up, +Z when looking straight down),
// OpenGL clip conventions: the renderer's own camera.
inline CameraView look_at(const Vec3& eye, const Vec3& target, int width = 1280, int height = 720,
                          float fov_y_rad = 1.0471976f, float near_m = 0.1f, float far_m = 1000.f) {
  const Vec3 f = (target - eye).normalized();
  const Vec3 up = std::abs(f.dot(Vec3::UnitY())) > 0.99f ? Vec3::UnitZ() : Vec3::UnitY();
  return render::make_camera_view(eye, target, up, fov_y_rad, width, height, near_m, far_m);
}

}  // namespace tourmap::crowd::test_models
