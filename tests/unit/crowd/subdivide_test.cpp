#include "crowd/subdivide.hpp"

#include "crowd/gltf_loader.hpp"
#include "crowd/skinning.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace tourmap::crowd {
namespace {

// A static-looking model over the given triangles: joint i = vertex i with weight 1 (one
// joint per vertex, so the stencils can be read back from the weights), colours black.
SkinnedModel mesh_model(const std::vector<Vec3>& positions, const std::vector<std::uint32_t>& indices) {
  SkinnedModel m;
  m.positions = positions;
  m.normals.assign(positions.size(), Vec3::UnitY());
  m.colors.assign(positions.size(), {0, 0, 0, 255});
  for (std::size_t v = 0; v < positions.size(); ++v) {
    m.joints.push_back({static_cast<std::uint16_t>(v), 0, 0, 0});
    m.weights.push_back({1, 0, 0, 0});
    m.skeleton.joint_names.push_back(std::to_string(v));  // ("j" + ... trips a GCC 12 -Wrestrict false positive)
    m.skeleton.parent.push_back(-1);
    m.skeleton.inverse_bind.push_back(Eigen::Matrix4f::Identity());
  }
  m.indices = indices;
  return m;
}

// Regular tetrahedron centred at the origin, faces oriented consistently.
SkinnedModel tetrahedron() {
  return mesh_model({Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)},
                    {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2});
}

TEST(Subdivide, TetrahedronFollowsLoopStencils) {
  SkinnedModel m = tetrahedron();
  m.colors[0] = {255, 0, 0, 255};
  const SkinnedModel s = subdivide(m, 1);
  ASSERT_EQ(s.triangle_count(), 16u);
  ASSERT_EQ(s.vertex_count(), 10u);  // 4 old + 6 edge vertices
  // Even vertices, valence 3: beta = 3/16, v' = 7/16 v + 3/16 (sum of the others) = v / 4
  // because the four vertices sum to zero.
  for (std::size_t v = 0; v < 4; ++v) EXPECT_TRUE(s.positions[v].isApprox(m.positions[v] / 4, 1e-6f)) << v;
  // Odd vertices: 3/8 (a + b) + 1/8 (c + d) = (a + b) / 4 for the same reason.
  std::vector<Vec3> expected;
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = a + 1; b < 4; ++b) expected.push_back((m.positions[a] + m.positions[b]) / 4);
  for (std::size_t v = 4; v < 10; ++v) {
    const auto hit = std::find_if(expected.begin(), expected.end(),
                                  [&](const Vec3& e) { return e.isApprox(s.positions[v], 1e-6f); });
    ASSERT_NE(hit, expected.end()) << "edge vertex " << v;
    expected.erase(hit);
  }
  // The same stencils on the skin: even vertex 0 = 7/16 joint 0 + 3/16 each neighbour.
  EXPECT_EQ(s.joints[0][0], 0);
  EXPECT_FLOAT_EQ(s.weights[0][0], 7.f / 16);
  EXPECT_FLOAT_EQ(s.weights[0][1], 3.f / 16);
  EXPECT_FLOAT_EQ(s.weights[0][2], 3.f / 16);
  EXPECT_FLOAT_EQ(s.weights[0][3], 3.f / 16);
  EXPECT_FLOAT_EQ(s.weights[4][0], 3.f / 8);  // an edge vertex: 3/8, 3/8, 1/8, 1/8
  EXPECT_FLOAT_EQ(s.weights[4][1], 3.f / 8);
  EXPECT_FLOAT_EQ(s.weights[4][2], 1.f / 8);
  EXPECT_FLOAT_EQ(s.weights[4][3], 1.f / 8);
  // ... and on the colours: 7/16 of 255 at vertex 0, 3/16 of 255 at its neighbours.
  EXPECT_EQ(s.colors[0][0], 112);
  EXPECT_EQ(s.colors[1][0], 48);
  // Outward orientation is kept: every new triangle's normal points away from the centre.
  for (std::size_t t = 0; t < s.triangle_count(); ++t) {
    const Vec3 a = s.positions[s.indices[3 * t]], b = s.positions[s.indices[3 * t + 1]],
               c = s.positions[s.indices[3 * t + 2]];
    EXPECT_GT((b - a).cross(c - a).dot(a + b + c), 0.f) << t;
  }
}

TEST(Subdivide, BoundaryEdgesUseTheCreaseRules) {
  const SkinnedModel m = mesh_model({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {0, 1, 2});
  const SkinnedModel s = subdivide(m, 1);
  ASSERT_EQ(s.vertex_count(), 6u);
  ASSERT_EQ(s.triangle_count(), 4u);
  // Boundary vertex: 3/4 itself + 1/8 each boundary neighbour; boundary edge: the midpoint.
  EXPECT_TRUE(s.positions[0].isApprox(Vec3(0.125f, 0.125f, 0), 1e-6f));
  EXPECT_TRUE(s.positions[1].isApprox(Vec3(0.75f, 0.125f, 0), 1e-6f));
  std::vector<Vec3> midpoints{Vec3(0.5f, 0, 0), Vec3(0, 0.5f, 0), Vec3(0.5f, 0.5f, 0)};
  for (std::size_t v = 3; v < 6; ++v)
    EXPECT_TRUE(std::any_of(midpoints.begin(), midpoints.end(), [&](const Vec3& p) {
      return p.isApprox(s.positions[v]);
    })) << s.positions[v].transpose();
}

TEST(Subdivide, KeepsTheFourLargestInfluencesRenormalised) {
  // Hexagonal fan: centre 0 has 6 ring neighbours, each on its own joint. Loop's beta for
  // valence 6 is 1/16, so the centre blends 10/16 of joint 0 with 1/16 of six more joints.
  std::vector<Vec3> p{Vec3::Zero()};
  for (int i = 0; i < 6; ++i) {
    const float a = static_cast<float>(i) * std::numbers::pi_v<float> / 3;
    p.emplace_back(std::cos(a), std::sin(a), 0);
  }
  std::vector<std::uint32_t> idx;
  for (std::uint32_t i = 1; i <= 6; ++i) idx.insert(idx.end(), {0, i, i % 6 + 1});
  const SkinnedModel s = subdivide(mesh_model(p, idx), 1);
  // Kept: joint 0 (10/16) and the three lowest-numbered of the tied 1/16 joints; sum 13/16.
  EXPECT_EQ(s.joints[0], (std::array<std::uint16_t, 4>{0, 1, 2, 3}));
  EXPECT_NEAR(s.weights[0][0], 10.f / 13, 1e-6f);
  for (std::size_t k = 1; k < 4; ++k) EXPECT_NEAR(s.weights[0][k], 1.f / 13, 1e-6f);
}

TEST(Subdivide, RejectsBadLevelsAndInput) {
  const SkinnedModel m = tetrahedron();
  EXPECT_THROW(subdivide(m, -1), std::invalid_argument);
  EXPECT_THROW(subdivide(m, 7), std::invalid_argument);
  EXPECT_EQ(subdivide(m, 0).triangle_count(), m.triangle_count());
  SkinnedModel bad = m;
  bad.indices[5] = 99;
  EXPECT_THROW(subdivide(bad, 1), std::invalid_argument);
  bad = m;
  bad.indices[1] = bad.indices[0];
  EXPECT_THROW(subdivide(bad, 1), std::invalid_argument);
}

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const float d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const float d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const float denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

TEST(Subdivide, CesiumManStaysOnItsSurfaceInEveryPoseSampled) {
  const SkinnedModel m = load_skinned_model(test::data_file("models/humans/CesiumMan.glb"));
  for (int levels : {1, 2}) {
    const auto t0 = std::chrono::steady_clock::now();
    const SkinnedModel s = subdivide(m, levels);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[ info ] CesiumMan loop x%d: %zu vertices, %zu triangles in %.0f ms\n", levels, s.vertex_count(),
                s.triangle_count(), ms);
    ASSERT_EQ(s.triangle_count(), m.triangle_count() << (2 * levels));
    // A closed 2-manifold gains one vertex per edge (E = 3F/2).
    if (levels == 1) {
      EXPECT_EQ(s.vertex_count(), m.vertex_count() + 3 * m.triangle_count() / 2);
    }
    for (std::size_t v = 0; v < s.vertex_count(); ++v) {
      const auto& w = s.weights[v];
      ASSERT_NEAR(w[0] + w[1] + w[2] + w[3], 1.f, 1e-5f);
      for (std::size_t k = 0; k < 4; ++k) ASSERT_LT(s.joints[v][k], m.skeleton.parent.size());
    }
  }
  // Skinned in two poses, the subdivided surface stays within a fraction of an edge of the
  // skinned original (Loop smooths, so it moves off the flat triangles, but not far).
  const SkinnedModel s = subdivide(m, 1);
  double edge_sum = 0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3)
    edge_sum += (m.positions[m.indices[t]] - m.positions[m.indices[t + 1]]).norm();
  const double mean_edge = edge_sum / static_cast<double>(m.triangle_count());
  for (std::size_t pose : {std::size_t{0}, std::size_t{30}}) {
    std::vector<Vec3> orig, sub;
    skin_positions(m, m.animations[0].poses[pose], orig);
    skin_positions(s, m.animations[0].poses[pose], sub);
    double worst = 0, sum = 0;
    std::size_t n = 0;
    for (std::size_t v = 0; v < sub.size(); v += 7, ++n) {
      float best = std::numeric_limits<float>::max();
      for (std::size_t t = 0; t < m.indices.size(); t += 3)
        best = std::min(best, (sub[v] - closest_on_triangle(sub[v], orig[m.indices[t]], orig[m.indices[t + 1]],
                                                            orig[m.indices[t + 2]]))
                                  .squaredNorm());
      worst = std::max(worst, static_cast<double>(std::sqrt(best)));
      sum += std::sqrt(best);
    }
    std::printf(
        "[ info ] pose %zu: subdivided vertices off the original surface: mean %.4f m, max %.4f m "
        "(mean edge %.4f m)\n",
        pose, sum / static_cast<double>(n), worst, mean_edge);
    EXPECT_LT(sum / static_cast<double>(n), 0.1 * mean_edge);
    EXPECT_LT(worst, 0.5 * mean_edge);
    EXPECT_GT(worst, 0.0);  // smooth, not flat midpoint subdivision
  }
}

TEST(Subdivide, MannequinyLevelsOneAndTwo) {
  const SkinnedModel m = load_skinned_model(test::data_file("models/humans/Mannequiny.glb"));
  for (int levels : {1, 2}) {
    const auto t0 = std::chrono::steady_clock::now();
    const SkinnedModel s = subdivide(m, levels);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[ info ] Mannequiny loop x%d: %zu vertices, %zu triangles in %.0f ms\n", levels, s.vertex_count(),
                s.triangle_count(), ms);
    EXPECT_EQ(s.triangle_count(), m.triangle_count() << (2 * levels));
    EXPECT_EQ(s.animations.size(), m.animations.size());
    EXPECT_EQ(s.normals.size(), s.vertex_count());
  }
}

}  // namespace
}  // namespace tourmap::crowd
