#include "crowd/leaf_clusters.hpp"

#include "crowd/deformation_level.hpp"
#include "crowd_test_models.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

namespace tourmap::crowd {
namespace {

using test_models::make_arm;

void expect_partition(const LeafTriangles& leaves, std::size_t triangles, std::size_t s) {
  std::vector<int> count(triangles, 0);
  for (const auto& leaf : leaves) {
    EXPECT_FALSE(leaf.empty());
    EXPECT_LE(leaf.size(), s);
    for (std::uint32_t t : leaf) {
      ASSERT_LT(t, triangles);
      ++count[t];
    }
  }
  for (std::size_t t = 0; t < triangles; ++t) EXPECT_EQ(count[t], 1) << "triangle " << t;
}

// Level of the most deforming corner of each triangle (the corner that owns it).
std::vector<float> owner_levels(const SkinnedModel& m, const std::vector<float>& levels) {
  std::vector<float> out(m.triangle_count());
  for (std::size_t t = 0; t < out.size(); ++t)
    out[t] = std::max({levels[m.indices[3 * t]], levels[m.indices[3 * t + 1]], levels[m.indices[3 * t + 2]]});
  return out;
}

// Leaves whose owner levels span more than the 10% rule allows (seed +-10%, so max/min > 1.1/0.9),
// counting only levels above the rigid tolerance.
int mixed_leaves(const SkinnedModel& m, const LeafTriangles& leaves, const std::vector<float>& levels, float eps) {
  const std::vector<float> owner = owner_levels(m, levels);
  int mixed = 0;
  for (const auto& leaf : leaves) {
    float lo = 1e30f, hi = 0;
    for (std::uint32_t t : leaf) {
      lo = std::min(lo, owner[t]);
      hi = std::max(hi, owner[t]);
    }
    if (hi > eps && hi > (1.1f / 0.9f) * std::max(lo, eps) + 1e-6f) ++mixed;
  }
  return mixed;
}

TEST(LeafClusters, EveryTriangleInExactlyOneLeafOfAtMostS) {
  const SkinnedModel arm = make_arm();
  const std::vector<float> levels = deformation_levels(arm);
  for (int s : {100, 37, 1}) {
    ErrorAwareClusterOptions o;
    o.max_leaf_triangles = s;
    expect_partition(error_aware_leaf_clusters(arm, levels, o), arm.triangle_count(), static_cast<std::size_t>(s));
    expect_partition(octree_leaf_clusters(arm, s), arm.triangle_count(), static_cast<std::size_t>(s));
  }
}

TEST(LeafClusters, ErrorAwareLeavesDoNotMixElbowWithRigidParts) {
  const SkinnedModel arm = make_arm();
  const std::vector<float> levels = deformation_levels(arm);
  Box3 box;
  for (const Vec3& p : arm.positions) box.extend(p);
  ErrorAwareClusterOptions paper_rule;
  paper_rule.min_group_triangles = 0;  // the 10% rule alone
  const float eps = paper_rule.rigid_level_fraction * box.diagonal().norm();
  EXPECT_EQ(mixed_leaves(arm, error_aware_leaf_clusters(arm, levels, paper_rule), levels, eps), 0);
  // The check can fail: octree cells cut across the elbow and mix levels.
  const int octree_mixed = mixed_leaves(arm, octree_leaf_clusters(arm, paper_rule.max_leaf_triangles), levels, eps);
  EXPECT_GT(octree_mixed, 0);
  // Merging small groups (the default) mixes neighbouring bands of the elbow, but less than
  // the octree does, and never the elbow with a rigid part (below).
  const LeafTriangles error_aware = error_aware_leaf_clusters(arm, levels);
  EXPECT_LT(mixed_leaves(arm, error_aware, levels, eps), octree_mixed);
  for (const auto& leaf : error_aware) EXPECT_GE(leaf.size(), 25u);  // no fragments on the arm
  // No leaf holds both a rigid triangle (all corners ~0) and a clearly deforming one.
  const float top = *std::max_element(levels.begin(), levels.end());
  const std::vector<float> owner = owner_levels(arm, levels);
  for (const auto& leaf : error_aware) {
    const bool rigid = std::any_of(leaf.begin(), leaf.end(), [&](std::uint32_t t) { return owner[t] < 1e-5f; });
    const bool bending = std::any_of(leaf.begin(), leaf.end(), [&](std::uint32_t t) { return owner[t] > 0.1f * top; });
    EXPECT_FALSE(rigid && bending);
  }
}

TEST(LeafClusters, LeavesAreSpatiallyCompact) {
  // A rigid grid is one level group, so the median split yields 2^k equal, compact leaves.
  const SkinnedModel grid = test_models::make_static_grid(30, 3.f);  // 1800 triangles
  const LeafTriangles leaves = error_aware_leaf_clusters(grid, deformation_levels(grid));
  expect_partition(leaves, grid.triangle_count(), 100);
  EXPECT_EQ(leaves.size(), 32u);  // 1800 -> 900 -> 450 -> 225 -> 112/113 -> 56/57
  for (const auto& leaf : leaves) {
    Box3 b;
    for (std::uint32_t t : leaf)
      for (int k = 0; k < 3; ++k) b.extend(grid.positions[grid.indices[3 * t + static_cast<std::size_t>(k)]]);
    EXPECT_LT(b.diagonal().norm(), 1.5f);  // a 1/32 piece of a 3 x 3 grid, not a scattered set
  }
  const LeafTriangles octree = octree_leaf_clusters(grid, 100);
  expect_partition(octree, grid.triangle_count(), 100);
}

TEST(LeafClusters, UnweldedCopyGivesTheSameLeaves) {
  // Every triangle with its own three vertices (like Fox.glb): welding restores adjacency.
  const SkinnedModel arm = make_arm();
  SkinnedModel split = arm;
  split.positions.clear();
  split.normals.clear();
  split.colors.clear();
  split.joints.clear();
  split.weights.clear();
  split.indices.clear();
  for (std::uint32_t v : arm.indices) {
    split.indices.push_back(static_cast<std::uint32_t>(split.positions.size()));
    split.positions.push_back(arm.positions[v]);
    split.normals.push_back(arm.normals[v]);
    split.colors.push_back(arm.colors[v]);
    split.joints.push_back(arm.joints[v]);
    split.weights.push_back(arm.weights[v]);
  }
  auto sorted = [](LeafTriangles l) {
    for (auto& leaf : l) std::sort(leaf.begin(), leaf.end());
    std::sort(l.begin(), l.end());
    return l;
  };
  const LeafTriangles a = sorted(error_aware_leaf_clusters(arm, deformation_levels(arm)));
  const LeafTriangles b = sorted(error_aware_leaf_clusters(split, deformation_levels(split)));
  EXPECT_EQ(a.size(), b.size());
  EXPECT_EQ(a, b);
}

TEST(LeafClusters, BadArgumentsThrow) {
  const SkinnedModel arm = make_arm();
  ErrorAwareClusterOptions o;
  o.max_leaf_triangles = 0;
  EXPECT_THROW(error_aware_leaf_clusters(arm, deformation_levels(arm), o), std::invalid_argument);
  EXPECT_THROW(error_aware_leaf_clusters(arm, std::vector<float>(3, 0.f)), std::invalid_argument);
  EXPECT_THROW(octree_leaf_clusters(arm, 0), std::invalid_argument);
  SkinnedModel broken = arm;
  broken.indices.back() = 100000;
  EXPECT_THROW(octree_leaf_clusters(broken, 100), std::invalid_argument);
}

}  // namespace
}  // namespace tourmap::crowd
