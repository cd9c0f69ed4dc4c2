#include "crowd/pose_selection.hpp"

#include "crowd/gltf_loader.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

namespace tourmap::crowd {
namespace {

// Every index 0..n-1 in exactly one group, groups sorted ascending.
void expect_partition(const std::vector<std::vector<int>>& groups, int n) {
  std::vector<int> all;
  for (const auto& g : groups) {
    EXPECT_FALSE(g.empty());
    EXPECT_TRUE(std::is_sorted(g.begin(), g.end()));
    all.insert(all.end(), g.begin(), g.end());
  }
  std::sort(all.begin(), all.end());
  std::vector<int> expected(static_cast<std::size_t>(n));
  std::iota(expected.begin(), expected.end(), 0);
  EXPECT_EQ(all, expected);
}

double diagonal(const Eigen::MatrixXd& points, const std::vector<int>& g) {
  Eigen::RowVectorXd lo = points.row(g[0]), hi = lo;
  for (int i : g) {
    lo = lo.cwiseMin(points.row(i));
    hi = hi.cwiseMax(points.row(i));
  }
  return (hi - lo).norm();
}

TEST(GroupPoses, TwoSeparatedBlobsMakeTwoGroups) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  Eigen::MatrixXd p(20, 3);
  for (int i = 0; i < 20; ++i) p.row(i) << (i % 2 ? 10.0 : 0.0) + jitter(rng), jitter(rng), jitter(rng);
  const auto groups = group_poses(p, 0.5);
  ASSERT_EQ(groups.size(), 2u);
  expect_partition(groups, 20);
  for (const auto& g : groups) {
    ASSERT_EQ(g.size(), 10u);
    for (int i : g) EXPECT_EQ(i % 2, g[0] % 2);  // never mixes the blobs
  }
}

TEST(GroupPoses, LongChainIsMergedThenPartitioned) {
  // 50 points 0.1 apart: with d = 0.15 every neighbour pair is within d, so clustering makes
  // one group 4.9 long; partitioning must cut it into pieces of diagonal <= 1.5 d.
  const int n = 50;
  const double d = 0.15;
  Eigen::MatrixXd p(n, 2);
  for (int i = 0; i < n; ++i) p.row(i) << 0.1 * i, 0.0;
  const auto groups = group_poses(p, d);
  expect_partition(groups, n);
  // A piece of diagonal <= 0.225 holds at most 3 points spaced 0.1: at least ceil(50 / 3).
  EXPECT_GE(groups.size(), 17u);
  for (const auto& g : groups) EXPECT_LE(diagonal(p, g), 1.5 * d + 1e-12);
  // Median splits keep the pieces contiguous runs of the chain.
  for (const auto& g : groups) EXPECT_EQ(g.back() - g.front() + 1, static_cast<int>(g.size()));
}

TEST(GroupPoses, RepresentativeIsClosestToTheBoxCentre) {
  Eigen::MatrixXd p(4, 1);
  p << 0, 1, 10, 4.9;
  EXPECT_EQ(representative(p, {0, 1, 2}), 1);  // centre 5: 1 is 4 away, 0 is 5, 10 is 5
  EXPECT_EQ(representative(p, {0, 1, 2, 3}), 3);
  EXPECT_EQ(representative(p, {2}), 2);
  EXPECT_THROW(representative(p, {}), std::invalid_argument);
  EXPECT_THROW(representative(p, {4}), std::out_of_range);
}

TEST(GroupPoses, RejectsBadInput) {
  EXPECT_THROW(group_poses(Eigen::MatrixXd::Zero(3, 2), -1), std::invalid_argument);
  EXPECT_THROW(group_poses(Eigen::MatrixXd::Zero(3, 2), std::nan("")), std::invalid_argument);
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(3, 2);
  p(1, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(group_poses(p, 1), std::invalid_argument);
  EXPECT_TRUE(group_poses(Eigen::MatrixXd(0, 2), 1).empty());
  EXPECT_EQ(group_poses(Eigen::MatrixXd::Zero(5, 2), 0).size(), 1u);  // identical points
}

// One joint carrying a rigid body that only travels: root-motion removal must see one pose.
TEST(PoseDistances, PureRootTravelIsNoPoseChange) {
  SkinnedModel m;
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 2, 0)};
  m.normals.assign(3, Vec3::UnitY());
  m.colors.assign(3, {255, 255, 255, 255});
  m.joints.assign(3, {0, 0, 0, 0});
  m.weights.assign(3, {1, 0, 0, 0});
  m.indices = {0, 1, 2};
  m.skeleton = {{"root"}, {-1}, {Eigen::Matrix4f::Identity()}};
  Animation walk;
  for (int k = 0; k < 10; ++k) {
    const Affine g = Eigen::Translation3f(0.5f * static_cast<float>(k), 0, 0) *
                     Eigen::AngleAxisf(0.1f * static_cast<float>(k), Vec3::UnitY());
    walk.poses.push_back(Pose{{g}, {g}});
  }
  m.animations = {walk};
  const Eigen::MatrixXd d = pose_distances(m, 0);
  ASSERT_EQ(d.rows(), 10);
  EXPECT_LT(d.maxCoeff(), 1e-5);
  const PoseSelection sel = select_poses(m, 0);
  EXPECT_EQ(sel.representatives.size(), 1u);
  EXPECT_THROW(pose_distances(m, 1), std::out_of_range);
}

TEST(SelectPoses, CesiumManWalkHasAFewRepresentatives) {
  const SkinnedModel m = load_skinned_model(test::data_file("models/humans/CesiumMan.glb"));
  const PoseSelection sel = select_poses(m, 0, 0.2f, 9);
  const int n = static_cast<int>(m.animations[0].poses.size());
  std::printf("[ info ] CesiumMan walk: %zu representative poses of %d (d = %.3f m, %zu sample vertices)\n",
              sel.representatives.size(), n, sel.d, sel.sample_vertices);
  EXPECT_EQ(sel.pose_count, static_cast<std::size_t>(n));
  EXPECT_EQ(sel.points.rows(), n);
  EXPECT_EQ(sel.points.cols(), 9);
  Box3 bind;
  for (const Vec3& p : m.positions) bind.extend(p);
  EXPECT_NEAR(sel.d, 0.2 * bind.diagonal().norm(), 1e-5);
  // A walk cycle: more than one pose group, far fewer groups than poses.
  EXPECT_GE(sel.representatives.size(), 3u);
  EXPECT_LE(sel.representatives.size(), static_cast<std::size_t>(n / 4));
  ASSERT_EQ(sel.groups.size(), sel.representatives.size());
  expect_partition(sel.groups, n);
  EXPECT_TRUE(std::is_sorted(sel.representatives.begin(), sel.representatives.end()));
  for (std::size_t g = 0; g < sel.groups.size(); ++g) {
    EXPECT_TRUE(std::binary_search(sel.groups[g].begin(), sel.groups[g].end(), sel.representatives[g]));
    EXPECT_LE(diagonal(sel.points, sel.groups[g]), 1.5 * sel.d + 1e-9);
  }
  // Pose distances: a symmetric matrix with a zero diagonal and real motion in it.
  const Eigen::MatrixXd d = pose_distances(m, 0);
  EXPECT_TRUE(d.isApprox(d.transpose()));
  EXPECT_EQ(d.diagonal().norm(), 0.0);
  EXPECT_GT(d.maxCoeff(), sel.d);
  // Smaller d, more representatives.
  EXPECT_GT(select_poses(m, 0, 0.1f).representatives.size(), sel.representatives.size());
}

}  // namespace
}  // namespace tourmap::crowd
