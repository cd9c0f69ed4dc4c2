// Measured cluster errors (sec. 3.5.1, ClusterError::measured): the point-triangle distance and
// BVH they rest on, and the errors of built hierarchies against brute force. build/bench/crowd_bench
// prints the quadric-vs-measured cut sizes on the scenes' characters.

#include "crowd/cluster_error.hpp"
#include "crowd/gltf_loader.hpp"
#include "crowd/hierarchy_build.hpp"
#include "crowd/hierarchy_io.hpp"
#include "crowd/lod_cut.hpp"
#include "crowd/subdivide.hpp"
#include "crowd/triangle_bvh.hpp"
#include "crowd_test_models.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <stdexcept>

namespace tourmap::crowd {
namespace {

float brute_distance(const Vec3& q, const std::vector<Vec3>& x, const std::vector<std::uint32_t>& tris) {
  float best = std::numeric_limits<float>::infinity();
  for (std::size_t t = 0; t < tris.size(); t += 3)
    best = std::min(best, point_triangle_distance_sq(q, x[tris[t]], x[tris[t + 1]], x[tris[t + 2]]));
  return std::sqrt(best);
}

TEST(PointTriangleDistance, RegionsOfTheTriangle) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  EXPECT_NEAR(point_triangle_distance_sq(Vec3(0.5f, 0.5f, 3), a, b, c), 9.f, 1e-5f);    // above the face
  EXPECT_NEAR(point_triangle_distance_sq(Vec3(-1, -1, 0), a, b, c), 2.f, 1e-5f);        // beyond corner a
  EXPECT_NEAR(point_triangle_distance_sq(Vec3(3, -1, 0), a, b, c), 2.f, 1e-5f);         // beyond corner b
  EXPECT_NEAR(point_triangle_distance_sq(Vec3(1, -2, 1), a, b, c), 5.f, 1e-5f);         // beyond edge ab
  EXPECT_NEAR(point_triangle_distance_sq(Vec3(2, 2, 0), a, b, c), 2.f, 1e-5f);          // beyond edge bc
  EXPECT_NEAR(point_triangle_distance_sq(Vec3(-3, 1, 0), a, b, c), 9.f, 1e-5f);         // beyond edge ca
  // Degenerate: collinear corners, and all three at one point.
  EXPECT_NEAR(point_triangle_distance_sq(Vec3(1, 1, 0), a, b, Vec3(1, 0, 0)), 1.f, 1e-5f);
  EXPECT_NEAR(point_triangle_distance_sq(Vec3(3, 0, 0), a, b, Vec3(1, 0, 0)), 1.f, 1e-5f);
  EXPECT_NEAR(point_triangle_distance_sq(Vec3(0, 0, 2), a, a, a), 4.f, 1e-5f);
}

TEST(PointTriangleDistance, AgreesWithDenseSamplingOfTheTriangle) {
  // The exact distance is at most the distance to any sampled point of the triangle, and at
  // least that minus the sampling spacing.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  constexpr int n = 60;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Vec3 q = 1.5f * Vec3(u(rng), u(rng), u(rng));
    float sampled = std::numeric_limits<float>::infinity();
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const float s = float(i) / n, t = float(j) / n;
        sampled = std::min(sampled, (q - (a + s * (b - a) + t * (c - a))).norm());
      }
    const float spacing = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()}) / n;
    const float exact = std::sqrt(point_triangle_distance_sq(q, a, b, c));
    EXPECT_LE(exact, sampled + 1e-5f) << "trial " << trial;
    EXPECT_GE(exact, sampled - spacing) << "trial " << trial;
  }
}

TEST(TriangleBvh, NearestDistanceMatchesBruteForceAndHonoursEnough) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<Vec3> x;
  std::vector<std::uint32_t> tris;
  for (std::uint32_t t = 0; t < 300; ++t) {  // small triangles scattered in the unit cube
    const Vec3 o(u(rng), u(rng), u(rng));
    for (int k = 0; k < 3; ++k) x.push_back(o + 0.05f * Vec3(u(rng), u(rng), u(rng)));
    tris.insert(tris.end(), {3 * t, 3 * t + 1, 3 * t + 2});
  }
  TriangleBvh bvh;
  EXPECT_EQ(bvh.distance(Vec3::Zero()), std::numeric_limits<float>::infinity());  // empty
  bvh.build(x, tris);
  EXPECT_EQ(bvh.triangle_count(), 300u);
  for (int i = 0; i < 500; ++i) {
    const Vec3 q(1.4f * u(rng) - 0.2f, 1.4f * u(rng) - 0.2f, 1.4f * u(rng) - 0.2f);
    const float truth = brute_distance(q, x, tris);
    EXPECT_FLOAT_EQ(bvh.distance(q), truth);
    const float enough = 0.03f;
    const float quick = bvh.distance(q, enough);
    if (truth > enough) {
      EXPECT_FLOAT_EQ(quick, truth);
    } else {
      EXPECT_GE(quick, truth);
      EXPECT_LE(quick, enough);
    }
  }
  // Hints (the slot of the previous query's triangle, or a stale one) change nothing.
  std::uint32_t hint = 12345;
  for (int i = 0; i < 200; ++i) {
    const Vec3 q(u(rng), u(rng), u(rng));
    EXPECT_FLOAT_EQ(bvh.distance(q, 0, &hint), brute_distance(q, x, tris));
    EXPECT_LT(hint, 300u);
  }
  EXPECT_THROW(bvh.build(x, {0, 1}), std::invalid_argument);
  EXPECT_THROW(bvh.build(x, {0, 1, 900}), std::invalid_argument);
}

TEST(MaxDistanceToSimplified, BoundsTheTrueMaximumAsDocumented) {
  // Two poses of a bumpy sheet; the "simplified" surface is two big triangles over it.
  std::vector<std::vector<Vec3>> posed(2);
  std::vector<std::uint32_t> vertices, triangles;
  constexpr std::uint32_t n = 20;
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = 0; j < n; ++j) {
      const float fx = float(i) / (n - 1), fz = float(j) / (n - 1);
      posed[0].emplace_back(fx, 0.1f * std::sin(6 * fx) * std::cos(5 * fz), fz);
      posed[1].emplace_back(fx, 0.3f * fx * fz, fz);
      vertices.push_back(i * n + j);
      if (i + 1 < n && j + 1 < n) triangles.insert(triangles.end(), {i * n + j, i * n + j + 1, (i + 1) * n + j});
    }
  const std::vector<std::uint32_t> simplified{0, 19, 399, 0, 399, 380};  // corners (0,0) (0,1) (1,1) (1,0)
  float from_vertices = 0, from_centroids = 0;
  for (const auto& x : posed) {
    for (std::uint32_t v : vertices) from_vertices = std::max(from_vertices, brute_distance(x[v], x, simplified));
    for (std::size_t t = 0; t < triangles.size(); t += 3) {
      const Vec3 centroid = (x[triangles[t]] + x[triangles[t + 1]] + x[triangles[t + 2]]) / 3.f;
      from_centroids = std::max(from_centroids, brute_distance(centroid, x, simplified));
    }
  }
  ASSERT_GT(from_vertices, 0.05f);
  TriangleBvh bvh;
  EXPECT_FLOAT_EQ(max_distance_to_simplified(posed, simplified, vertices, {}, 0, bvh), from_vertices);
  EXPECT_FLOAT_EQ(max_distance_to_simplified(posed, simplified, {}, triangles, 0, bvh), from_centroids);
  const float truth = std::max(from_vertices, from_centroids);
  EXPECT_FLOAT_EQ(max_distance_to_simplified(posed, simplified, vertices, triangles, 0, bvh), truth);
  for (float known : {0.5f * truth, 2.f * truth}) {
    const float r = max_distance_to_simplified(posed, simplified, vertices, triangles, known, bvh);
    EXPECT_GE(r, truth);
    EXPECT_LE(r, std::max(truth, known));
  }
  EXPECT_EQ(max_distance_to_simplified(posed, simplified, {}, {}, 0, bvh), 0.f);
  EXPECT_THROW(max_distance_to_simplified(posed, {}, vertices, {}, 0, bvh), std::invalid_argument);
  EXPECT_THROW(max_distance_to_simplified(posed, simplified, {400}, {}, 0, bvh), std::invalid_argument);
  EXPECT_THROW(max_distance_to_simplified(posed, simplified, {}, {0, 1}, 0, bvh), std::invalid_argument);
}

// 1e-6 of the bind-pose bbox diagonal: distances below it are float noise of skinned positions
// (the build does not resolve them, see hierarchy_build.cpp).
float resolution_of(const SkinnedModel& m) {
  Box3 bind;
  for (const Vec3& p : m.positions) bind.extend(p);
  return 1e-6f * bind.diagonal().norm();
}

// Original triangles (vertex ids, 3 each) below every cluster: its leaves' triangles.
std::vector<std::vector<std::uint32_t>> original_triangles_below(const ClusterHierarchy& h) {
  std::vector<std::vector<std::uint32_t>> below(h.clusters.size());
  std::vector<int> order{h.root};
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Cluster& c = h.clusters[static_cast<std::size_t>(order[i])];
    if (!c.is_leaf()) order.insert(order.end(), c.children.begin(), c.children.end());
  }
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const Cluster& c = h.clusters[static_cast<std::size_t>(*it)];
    auto& mine = below[static_cast<std::size_t>(*it)];
    if (c.is_leaf()) {
      mine.assign(h.indices.begin() + c.first_index, h.indices.begin() + c.first_index + c.index_count);
    } else {
      for (int k : c.children) mine.insert(mine.end(), below[static_cast<std::size_t>(k)].begin(), below[static_cast<std::size_t>(k)].end());
    }
  }
  return below;
}

std::vector<std::uint32_t> triangles_of(const ClusterHierarchy& h, std::size_t c) {
  const Cluster& cl = h.clusters[c];
  return {h.indices.begin() + cl.first_index, h.indices.begin() + cl.first_index + cl.index_count};
}

std::vector<const Pose*> representative_pose_list(const SkinnedModel& m, const std::vector<std::vector<int>>& reps) {
  std::vector<const Pose*> poses;
  for (std::size_t a = 0; a < reps.size(); ++a)
    for (int p : reps[a]) poses.push_back(&m.animations[a].poses[static_cast<std::size_t>(p)]);
  return poses;
}

// Checks every parent of a hierarchy built with measured errors against brute force over the
// original triangles below it (their corners and centroids; all of them, or a random subset of
// `max_triangles`) in every representative pose: the error sphere's diameter covers the largest
// distance, and where the measurement set the error (above the children's) and every triangle
// was checked, it is that distance. Returns the number of parents checked that way.
std::size_t expect_errors_cover_brute_force(const SkinnedModel& m, const ClusterHierarchy& h,
                                            const std::vector<std::vector<int>>& reps, std::size_t max_triangles) {
  const auto posed = posed_positions(m, representative_pose_list(m, reps));
  const auto below = original_triangles_below(h);
  const float resolution = resolution_of(m);
  std::mt19937 rng(5);
  std::size_t exact = 0;
  for (std::size_t i = 0; i < h.clusters.size(); ++i) {
    const Cluster& c = h.clusters[i];
    if (c.is_leaf()) continue;
    std::vector<std::size_t> picked(below[i].size() / 3);
    for (std::size_t t = 0; t < picked.size(); ++t) picked[t] = t;
    const bool all = picked.size() <= max_triangles;
    if (!all) {
      std::shuffle(picked.begin(), picked.end(), rng);
      picked.resize(max_triangles);
    }
    const auto tris = triangles_of(h, i);
    float truth = 0;
    for (const auto& x : posed)
      for (std::size_t t : picked) {
        const Vec3 a = x[below[i][3 * t]], b = x[below[i][3 * t + 1]], d = x[below[i][3 * t + 2]];
        for (const Vec3& q : {a, b, d, Vec3((a + b + d) / 3.f)}) truth = std::max(truth, brute_distance(q, x, tris));
      }
    EXPECT_GE(2 * c.error, truth * (1 - 1e-6f)) << "cluster " << i;
    const float children = std::max(h.clusters[static_cast<std::size_t>(c.children[0])].error,
                                    h.clusters[static_cast<std::size_t>(c.children[1])].error);
    if (all && c.error > children) {
      ++exact;
      EXPECT_LE(2 * c.error, std::max(truth, resolution) * (1 + 1e-6f)) << "cluster " << i;
    }
  }
  return exact;
}

HierarchyOptions with_metric(ClusterError metric, LeafClustering clustering = LeafClustering::error_aware) {
  HierarchyOptions o;
  o.clustering = clustering;
  o.error_metric = metric;
  return o;
}

// Per cluster: measured <= quadric, up to float noise where both are ~0 (the simplification does
// not depend on the metric, so both trees are the same). Prints the root errors and the ratios.
void expect_measured_below_quadric(const char* name, const SkinnedModel& m, const ClusterHierarchy& quadric,
                                   const ClusterHierarchy& measured) {
  const float noise = resolution_of(m);
  ASSERT_EQ(quadric.indices, measured.indices);
  ASSERT_EQ(quadric.clusters.size(), measured.clusters.size());
  std::vector<double> ratios;
  for (std::size_t i = 0; i < quadric.clusters.size(); ++i) {
    ASSERT_EQ(quadric.clusters[i].children, measured.clusters[i].children);
    EXPECT_LE(measured.clusters[i].error, quadric.clusters[i].error + noise) << name << " cluster " << i;
    if (quadric.clusters[i].error > noise) ratios.push_back(double(measured.clusters[i].error) / double(quadric.clusters[i].error));
  }
  std::sort(ratios.begin(), ratios.end());
  const auto root = static_cast<std::size_t>(quadric.root);
  std::printf("[ %s ] root error radius: quadric %.4f, measured %.4f; measured/quadric per cluster: median %.3f, max %.3f\n",
              name, double(quadric.clusters[root].error), double(measured.clusters[root].error),
              ratios.empty() ? 0.0 : ratios[ratios.size() / 2], ratios.empty() ? 0.0 : ratios.back());
}

TEST(MeasuredClusterError, ArmErrorsCoverTheTrueDistanceAndStayBelowTheQuadric) {
  const SkinnedModel arm = test_models::make_arm();
  const auto reps = test_models::all_poses(arm);
  for (LeafClustering clustering : {LeafClustering::error_aware, LeafClustering::octree}) {
    const ClusterHierarchy measured = build_hierarchy(arm, with_metric(ClusterError::measured, clustering), reps);
    EXPECT_NO_THROW(validate_hierarchy(measured, arm.vertex_count()));  // monotonic, leaves 0
    for (const Cluster& c : measured.clusters) {
      if (c.is_leaf()) {
        EXPECT_EQ(c.error, 0.f);
      }
    }
    EXPECT_GT(measured.clusters[static_cast<std::size_t>(measured.root)].error, 0.f);
    // Brute force in all 20 poses, over every original triangle below the lower parents and
    // 160 random ones below the upper.
    EXPECT_GT(expect_errors_cover_brute_force(arm, measured, reps, 160), 0u);
    const ClusterHierarchy quadric = build_hierarchy(arm, with_metric(ClusterError::quadric, clustering), reps);
    expect_measured_below_quadric(clustering == LeafClustering::octree ? "arm octree" : "arm error-aware", arm, quadric,
                                  measured);
  }
}

TEST(MeasuredClusterError, FlatAndRigidPartsHaveNoError) {
  // A flat grid moving rigidly through several poses: every simplification stays in the plane.
  SkinnedModel grid = test_models::make_static_grid(30, 3.f);
  Animation& anim = grid.animations[0];
  for (int k = 1; k < 5; ++k) {
    Pose pose;
    const Affine g(Eigen::Translation3f(0.2f * float(k), 0.5f, 0) * Eigen::AngleAxisf(0.3f * float(k), Vec3(1, 1, 0).normalized()));
    pose.skinning = {g};
    pose.global = {g};
    anim.poses.push_back(pose);
  }
  const ClusterHierarchy h = build_hierarchy(grid, {}, test_models::all_poses(grid));
  for (const Cluster& c : h.clusters) EXPECT_LT(c.error, 1e-5f);

  // The strip bends at the elbow: clusters away from it do not deform, so they stay flat.
  test_models::ArmSpec spec;
  spec.shape = test_models::ArmShape::strip;
  spec.around = 2;
  const SkinnedModel strip = test_models::make_arm(spec);
  HierarchyOptions o;
  o.max_leaf_triangles = 10;
  const ClusterHierarchy bent = build_hierarchy(strip, o, test_models::all_poses(strip));
  std::size_t rigid = 0;
  for (const Cluster& c : bent.clusters)
    if (!c.is_leaf() && c.deformation_level < 1e-5f) {
      ++rigid;
      EXPECT_LT(c.error, 1e-5f);
    }
  EXPECT_GT(rigid, 0u);
  EXPECT_GT(bent.clusters[static_cast<std::size_t>(bent.root)].error, 0.01f);  // across the elbow
}

TEST(MeasuredClusterError, CesiumManErrorsCoverTheTrueDistanceAndStayBelowTheQuadric) {
  const SkinnedModel m = load_skinned_model(tourmap::test::data_file("models/humans/CesiumMan.glb"));
  // A fixed set of representative poses (pose selection is tested elsewhere): 6 spread over the walk.
  ASSERT_EQ(m.animations.size(), 1u);
  const int n = static_cast<int>(m.animations[0].poses.size());
  ASSERT_GE(n, 6);
  std::vector<std::vector<int>> reps{{}};
  for (int k = 0; k < 6; ++k) reps[0].push_back(k * (n - 1) / 5);
  const ClusterHierarchy measured = build_hierarchy(m, with_metric(ClusterError::measured), reps);
  EXPECT_NO_THROW(validate_hierarchy(measured, m.vertex_count()));
  EXPECT_GT(expect_errors_cover_brute_force(m, measured, reps, 200), 0u);
  const ClusterHierarchy quadric = build_hierarchy(m, with_metric(ClusterError::quadric), reps);
  expect_measured_below_quadric("CesiumMan", m, quadric, measured);
}

}  // namespace
}  // namespace tourmap::crowd
