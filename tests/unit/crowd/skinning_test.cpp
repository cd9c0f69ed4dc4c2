#include "crowd/skinning.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tourmap::crowd {
namespace {

// Two joints: joint 0 at the origin, joint 1 bound at (1,0,0). The pose keeps joint 0 and
// rotates joint 1 by 90 degrees about +Z around its own origin, so
// M_1 = G_1 * B_1^-1 = T(1,0,0) * Rz(90) * T(-1,0,0).
SkinnedModel two_joint_model() {
  SkinnedModel m;
  m.skeleton.joint_names = {"j0", "j1"};
  m.skeleton.parent = {-1, 0};
  m.skeleton.inverse_bind = {Eigen::Matrix4f::Identity(), Affine(Eigen::Translation3f(-1, 0, 0)).matrix()};
  m.positions = {Vec3(2, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(0.5f, 0.3f, 0)};
  m.normals = {Vec3(0, 1, 0), Vec3(0, 1, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.colors.assign(4, {255, 255, 255, 255});
  m.joints = {{0, 1, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}, {0, 0, 0, 0}};
  m.weights = {{0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}};
  m.indices = {0, 1, 3, 1, 2, 3};
  Pose pose;
  const Affine g1 = Eigen::Translation3f(1, 0, 0) * Eigen::AngleAxisf(std::numbers::pi_v<float> / 2, Vec3::UnitZ());
  pose.global = {Affine::Identity(), g1};
  pose.skinning = {Affine::Identity(), g1 * Affine(m.skeleton.inverse_bind[1])};
  Animation anim;
  anim.name = "bend";
  anim.poses = {pose};
  m.animations = {anim};
  return m;
}

void expect_near(const Vec3& got, const Vec3& want) {
  EXPECT_NEAR(got.x(), want.x(), 1e-6f);
  EXPECT_NEAR(got.y(), want.y(), 1e-6f);
  EXPECT_NEAR(got.z(), want.z(), 1e-6f);
}

TEST(Skinning, BlendsTwoJointsAsComputedByHand) {
  const SkinnedModel m = two_joint_model();
  const Pose& pose = m.animations[0].poses[0];
  // Vertex (2,0,0), weights 0.5/0.5: joint 0 leaves it at (2,0,0); joint 1 turns the offset
  // (1,0,0) from its origin into (0,1,0), i.e. (1,1,0). Half of each: (1.5, 0.5, 0).
  expect_near(skin_position(m, 0, pose), Vec3(1.5f, 0.5f, 0));
  // The joint's own origin does not move; a point fully on joint 1 turns with it.
  expect_near(skin_position(m, 1, pose), Vec3(1, 0, 0));
  expect_near(skin_position(m, 2, pose), Vec3(1, 1, 0));
  expect_near(skin_position(m, 3, pose), Vec3(0.5f, 0.3f, 0));
  // Normal (0,1,0): joint 1 turns it to (-1,0,0); the blend (-0.5,0.5,0) renormalised.
  const float h = std::sqrt(0.5f);
  expect_near(skin_normal(m, 0, pose), Vec3(-h, h, 0));
  expect_near(skin_normal(m, 2, pose), Vec3(-1, 0, 0));
}

TEST(Skinning, BatchMatchesPerVertex) {
  const SkinnedModel m = two_joint_model();
  const Pose& pose = m.animations[0].poses[0];
  std::vector<Vec3> positions, normals;
  skin_positions(m, pose, positions);
  skin_normals(m, pose, normals);
  ASSERT_EQ(positions.size(), m.vertex_count());
  ASSERT_EQ(normals.size(), m.vertex_count());
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    expect_near(positions[v], skin_position(m, v, pose));
    expect_near(normals[v], skin_normal(m, v, pose));
  }
}

TEST(Skinning, RejectsBadVertexAndPose) {
  SkinnedModel m = two_joint_model();
  const Pose& pose = m.animations[0].poses[0];
  EXPECT_THROW(skin_position(m, 4, pose), std::out_of_range);
  Pose short_pose = pose;
  short_pose.skinning.pop_back();
  std::vector<Vec3> out;
  EXPECT_THROW(skin_positions(m, short_pose, out), std::invalid_argument);
  m.joints[1][0] = 7;  // a joint the skeleton does not have
  EXPECT_THROW(skin_positions(m, pose, out), std::invalid_argument);
}

}  // namespace
}  // namespace tourmap::crowd
