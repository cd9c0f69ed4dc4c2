#include "crowd/pose_quadric_simplify.hpp"

#include "crowd/mesh_topology.hpp"
#include "crowd/skinning.hpp"
#include "crowd_test_models.hpp"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

namespace tourmap::crowd {
namespace {

using test_models::ArmShape;
using test_models::ArmSpec;

std::vector<const Pose*> poses_of(const SkinnedModel& m, std::initializer_list<std::size_t> which = {}) {
  std::vector<const Pose*> out;
  const auto& poses = m.animations[0].poses;
  if (which.size() == 0) {
    for (const Pose& p : poses) out.push_back(&p);
  } else {
    for (std::size_t i : which) out.push_back(&poses[i]);
  }
  return out;
}

std::set<std::uint32_t> vertices_of(const std::vector<std::uint32_t>& indices) {
  return {indices.begin(), indices.end()};
}

TEST(PoseQuadricSimplify, FlatGridHalvesWithoutErrorOrNewVertices) {
  const SkinnedModel grid = test_models::make_static_grid(20, 2.f);  // 800 triangles
  PoseQuadricSimplifier simplifier(grid, canonical_vertices(grid), poses_of(grid));
  const SimplifyResult r = simplifier.simplify(grid.indices, 400, [](std::uint32_t) { return false; });
  EXPECT_TRUE(r.reached_target);
  EXPECT_LE(r.indices.size() / 3, 400u);
  EXPECT_GE(r.indices.size() / 3, 398u);  // a collapse removes one or two triangles
  EXPECT_LT(r.max_quadric_error, 1e-10);
  const auto before = vertices_of(grid.indices);
  for (std::uint32_t v : vertices_of(r.indices)) EXPECT_TRUE(before.count(v));
  // Still facing up: no triangle flipped.
  for (std::size_t t = 0; t < r.indices.size(); t += 3) {
    const Vec3& a = grid.positions[r.indices[t]];
    const Vec3 n = (grid.positions[r.indices[t + 1]] - a).cross(grid.positions[r.indices[t + 2]] - a);
    EXPECT_GT(n.dot(grid.normals[0]) * (grid.positions[grid.indices[1]] - grid.positions[grid.indices[0]])
                                           .cross(grid.positions[grid.indices[2]] - grid.positions[grid.indices[0]])
                                           .dot(grid.normals[0]),
              0.f);
  }
}

TEST(PoseQuadricSimplify, LockedVerticesSurvive) {
  const SkinnedModel grid = test_models::make_static_grid(20, 2.f);
  PoseQuadricSimplifier simplifier(grid, canonical_vertices(grid), poses_of(grid));
  auto locked = [](std::uint32_t v) { return v % 3 == 0; };
  const SimplifyResult r = simplifier.simplify(grid.indices, 100, locked);
  const auto kept = vertices_of(r.indices);
  for (std::uint32_t v : vertices_of(grid.indices))
    if (locked(v)) {
      EXPECT_TRUE(kept.count(v)) << "locked vertex " << v << " was removed";
    }
  // A third of the vertices locked: the target of 100 triangles cannot be met.
  EXPECT_FALSE(r.reached_target);
  EXPECT_GT(r.indices.size() / 3, 100u);
}

TEST(PoseQuadricSimplify, TargetAtOrAboveInputKeepsTheInput) {
  const SkinnedModel grid = test_models::make_static_grid(4, 1.f);
  PoseQuadricSimplifier simplifier(grid, canonical_vertices(grid), poses_of(grid));
  const SimplifyResult r = simplifier.simplify(grid.indices, grid.triangle_count(), [](std::uint32_t) { return false; });
  EXPECT_EQ(r.indices, grid.indices);
  EXPECT_TRUE(r.reached_target);
  EXPECT_EQ(r.collapses, 0u);
}

TEST(PoseQuadricSimplify, BentPosesRaiseTheErrorAndNothingFlips) {
  ArmSpec spec;
  spec.shape = ArmShape::strip;
  spec.around = 9;
  const SkinnedModel strip = test_models::make_arm(spec);  // 640 triangles, flat when straight
  const auto canonical = canonical_vertices(strip);
  const auto none = [](std::uint32_t) { return false; };
  PoseQuadricSimplifier straight(strip, canonical, poses_of(strip, {0}));
  PoseQuadricSimplifier all(strip, canonical, poses_of(strip));
  // Lines across the strip stay straight in every pose, so only collapses along it (between
  // elbow rings) cost anything; 13 ring lines are in the blend zone, so 16 triangles need some.
  const SimplifyResult rs = straight.simplify(strip.indices, 16, none);
  const SimplifyResult ra = all.simplify(strip.indices, 16, none);
  EXPECT_LT(rs.max_quadric_error, 1e-8);  // a flat strip in its only pose
  EXPECT_TRUE(rs.reached_target);
  EXPECT_TRUE(ra.reached_target);
  EXPECT_GT(ra.max_quadric_error, 1e-4);  // collapses along the bent elbow cost
  // In every pose, each remaining triangle faces the same side as the skinned vertex normals at
  // its corners (the strip's normal is +y in the bind pose).
  for (const Pose& pose : strip.animations[0].poses) {
    std::vector<Vec3> x, n;
    skin_positions(strip, pose, x);
    skin_normals(strip, pose, n);
    for (std::size_t t = 0; t < ra.indices.size(); t += 3) {
      const std::uint32_t a = ra.indices[t], b = ra.indices[t + 1], c = ra.indices[t + 2];
      const Vec3 face = (x[b] - x[a]).cross(x[c] - x[a]);
      const Vec3 bind_face = (strip.positions[b] - strip.positions[a]).cross(strip.positions[c] - strip.positions[a]);
      const float side = bind_face.dot(Vec3::UnitY()) > 0 ? 1.f : -1.f;  // winding of the strip
      EXPECT_GT(side * face.dot(n[a] + n[b] + n[c]), 0.f);
    }
  }
}

TEST(PoseQuadricSimplify, NonManifoldTrianglesAreKept) {
  // Three triangles on one edge (0-1): OpenMesh can not hold the third; it is kept as it is.
  SkinnedModel m = test_models::make_static_grid(1, 1.f);
  m.positions.emplace_back(0.5f, 1.f, 0.f);
  m.positions.emplace_back(0.5f, -1.f, 0.f);
  for (int k = 0; k < 2; ++k) {
    m.normals.emplace_back(0, 1, 0);
    m.colors.push_back({0, 0, 0, 255});
    m.joints.push_back({0, 0, 0, 0});
    m.weights.push_back({1, 0, 0, 0});
  }
  m.indices.insert(m.indices.end(), {0, 2, 4, 0, 2, 5});  // edge 0-2 now has four triangles
  PoseQuadricSimplifier simplifier(m, canonical_vertices(m), poses_of(m));
  const SimplifyResult r = simplifier.simplify(m.indices, 1, [](std::uint32_t) { return false; });
  EXPECT_FALSE(r.reached_target);
  EXPECT_EQ(r.indices.size() % 3, 0u);
  const auto kept = vertices_of(r.indices);
  EXPECT_TRUE(kept.count(4) || kept.count(5));
}

TEST(PoseQuadricSimplify, BadInputThrows) {
  const SkinnedModel grid = test_models::make_static_grid(2, 1.f);
  EXPECT_THROW(PoseQuadricSimplifier(grid, canonical_vertices(grid), {}), std::invalid_argument);
  EXPECT_THROW(PoseQuadricSimplifier(grid, {0, 1}, poses_of(grid)), std::invalid_argument);
  PoseQuadricSimplifier simplifier(grid, canonical_vertices(grid), poses_of(grid));
  EXPECT_THROW(simplifier.simplify({0, 1}, 0, [](std::uint32_t) { return false; }), std::invalid_argument);
  EXPECT_THROW(simplifier.simplify({0, 1, 99}, 0, [](std::uint32_t) { return false; }), std::invalid_argument);
  // Still usable after a rejected call.
  EXPECT_TRUE(simplifier.simplify(grid.indices, 4, [](std::uint32_t) { return false; }).reached_target);
}

}  // namespace
}  // namespace tourmap::crowd
