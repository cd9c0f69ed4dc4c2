#include "crowd/deformation_level.hpp"

#include "crowd_test_models.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace tourmap::crowd {
namespace {

using test_models::ArmSpec;
using test_models::make_arm;

TEST(DeformationLevel, InfluenceAncestorIsTheLeastCommonAncestor) {
  Skeleton s;
  s.parent = {-1, 0, 0, 1, 3, -1};  // 0 -> {1, 2}, 1 -> 3 -> 4; 5 is a second root
  EXPECT_EQ(influence_ancestor(s, {3, 0, 0, 0}, {1, 0, 0, 0}), 3);
  EXPECT_EQ(influence_ancestor(s, {4, 3, 0, 0}, {0.5f, 0.5f, 0, 0}), 3);
  EXPECT_EQ(influence_ancestor(s, {4, 2, 0, 0}, {0.5f, 0.5f, 0, 0}), 0);
  EXPECT_EQ(influence_ancestor(s, {4, 1, 2, 3}, {0.3f, 0.3f, 0, 0.4f}), 1);  // zero weight ignored
  EXPECT_EQ(influence_ancestor(s, {4, 5, 0, 0}, {0.5f, 0.5f, 0, 0}), -1);    // two trees
  EXPECT_EQ(influence_ancestor(s, {0, 0, 0, 0}, {0, 0, 0, 0}), -1);          // no influence
}

TEST(DeformationLevel, RigidPartsAreZeroDespiteRootMotion) {
  const SkinnedModel arm = make_arm();
  const std::vector<float> levels = deformation_levels(arm);
  ASSERT_EQ(levels.size(), arm.vertex_count());
  for (std::size_t v = 0; v < arm.vertex_count(); ++v) {
    const float x = arm.positions[v].x();
    if (x <= 0.7f || x >= 1.3f) {
      EXPECT_LT(levels[v], 1e-5f) << "vertex " << v << " at x = " << x;
    }
  }
}

TEST(DeformationLevel, ElbowVertexMatchesItsAnalyticTrajectory) {
  // A vertex at (1, r, 0) with weights 1/2, 1/2: in bone 0's frame it moves from (1, r) to
  // (1 - r/2, r/2) as the elbow bends 90 degrees, so its bbox diagonal is r/2 * sqrt(2).
  const ArmSpec spec;
  const SkinnedModel arm = make_arm(spec);
  const std::vector<float> levels = deformation_levels(arm);
  const std::size_t elbow_ring = static_cast<std::size_t>(spec.rings - 1) / 2;
  const std::size_t v = elbow_ring * static_cast<std::size_t>(spec.around);  // angle 0: (1, r, 0)
  ASSERT_NEAR(arm.positions[v].x(), 1.f, 1e-6f);
  ASSERT_NEAR(arm.positions[v].y(), spec.radius, 1e-6f);
  EXPECT_NEAR(levels[v], 0.5f * spec.radius * std::sqrt(2.f), 1e-4f);
  // The largest level is in the blend zone (x in (0.7, 1.3)); forearm-side vertices there still
  // have bone 0 as ancestor and swing around the elbow, so the peak is past x = 1.
  const auto worst = std::max_element(levels.begin(), levels.end()) - levels.begin();
  EXPECT_GT(arm.positions[static_cast<std::size_t>(worst)].x(), 1.f);
  EXPECT_LT(arm.positions[static_cast<std::size_t>(worst)].x(), 1.3f);
}

TEST(DeformationLevel, TrajectoryBoundsContainEveryPose) {
  const SkinnedModel arm = make_arm();
  const VertexTrajectories traj = vertex_trajectories(arm);
  for (const Pose& pose : arm.animations[0].poses)
    for (std::size_t v = 0; v < arm.vertex_count(); v += 7) {
      Vec3 x = Vec3::Zero();
      for (std::size_t k = 0; k < 2; ++k) x += arm.weights[v][k] * (pose.skinning[k] * arm.positions[v]);
      EXPECT_TRUE(traj.bounds[v].exteriorDistance(x) < 1e-5f);
    }
}

TEST(DeformationLevel, ScaledRigKeepsModelUnits) {
  // The same arm with its bone frames scaled by 100 (a centimetre rig under a 0.01 node would do
  // the opposite): the skinned mesh is unchanged, so the levels must be too.
  const SkinnedModel arm = make_arm();
  SkinnedModel scaled = arm;
  for (Pose& pose : scaled.animations[0].poses)
    for (Affine& g : pose.global) g = g * Eigen::Scaling(100.f);
  const std::vector<float> a = deformation_levels(arm), b = deformation_levels(scaled);
  for (std::size_t v = 0; v < a.size(); ++v) EXPECT_NEAR(a[v], b[v], 1e-4f) << "vertex " << v;
}

TEST(DeformationLevel, SkeletonCycleThrows) {
  Skeleton s;
  s.parent = {1, 0};
  EXPECT_THROW(influence_ancestor(s, {0, 1, 0, 0}, {0.5f, 0.5f, 0, 0}), std::invalid_argument);
}

TEST(DeformationLevel, StaticModelIsZero) {
  const SkinnedModel grid = test_models::make_static_grid(4);
  for (float l : deformation_levels(grid)) EXPECT_EQ(l, 0.f);
}

TEST(DeformationLevel, MismatchedPoseThrows) {
  SkinnedModel arm = make_arm();
  arm.animations[0].poses[3].global.pop_back();
  EXPECT_THROW(deformation_levels(arm), std::invalid_argument);
  SkinnedModel bad_joint = make_arm();
  bad_joint.joints[5][0] = 7;  // weight 1
  EXPECT_THROW(deformation_levels(bad_joint), std::invalid_argument);
}

}  // namespace
}  // namespace tourmap::crowd
