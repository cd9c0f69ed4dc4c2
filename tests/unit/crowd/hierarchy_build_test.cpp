#include "crowd/hierarchy_build.hpp"

#include "crowd/hierarchy_io.hpp"
#include "crowd/skinning.hpp"
#include "crowd_test_models.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <stdexcept>

namespace tourmap::crowd {
namespace {

using test_models::all_poses;
using test_models::ArmShape;
using test_models::ArmSpec;
using test_models::make_arm;

std::vector<std::uint32_t> triangles_of(const ClusterHierarchy& h, std::size_t c) {
  const Cluster& cl = h.clusters[c];
  return {h.indices.begin() + cl.first_index, h.indices.begin() + cl.first_index + cl.index_count};
}

// Leaf ids under each cluster.
std::vector<std::vector<int>> leaves_below(const ClusterHierarchy& h) {
  std::vector<std::vector<int>> below(h.clusters.size());
  // Children have smaller ids than parents in a built hierarchy, but do not rely on it.
  std::vector<int> order{h.root};
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Cluster& c = h.clusters[static_cast<std::size_t>(order[i])];
    if (!c.is_leaf()) order.insert(order.end(), c.children.begin(), c.children.end());
  }
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const Cluster& c = h.clusters[static_cast<std::size_t>(*it)];
    auto& mine = below[static_cast<std::size_t>(*it)];
    if (c.is_leaf()) {
      mine.push_back(*it);
    } else {
      for (int k : c.children) mine.insert(mine.end(), below[static_cast<std::size_t>(k)].begin(), below[static_cast<std::size_t>(k)].end());
    }
  }
  return below;
}

class ArmHierarchy : public ::testing::TestWithParam<LeafClustering> {
 protected:
  // Built once per clustering method for all tests of the suite.
  struct Built {
    SkinnedModel arm = make_arm();
    ClusterHierarchy h;
  };
  static const Built& built(LeafClustering method) {
    static std::map<LeafClustering, Built> cache;
    auto it = cache.find(method);
    if (it == cache.end()) {
      Built b;
      HierarchyOptions o;
      o.clustering = method;
      b.h = build_hierarchy(b.arm, o, all_poses(b.arm));
      it = cache.emplace(method, std::move(b)).first;
    }
    return it->second;
  }
  const SkinnedModel& arm = built(GetParam()).arm;
  const ClusterHierarchy& h = built(GetParam()).h;
};

TEST_P(ArmHierarchy, TreeShape) {
  EXPECT_NO_THROW(validate_hierarchy(h, arm.vertex_count()));
  int roots = 0;
  std::size_t leaves = 0;
  for (std::size_t i = 0; i < h.clusters.size(); ++i) {
    const Cluster& c = h.clusters[i];
    if (c.parent < 0) ++roots;
    if (c.is_leaf()) {
      ++leaves;
      EXPECT_EQ(c.error, 0.f);
      EXPECT_LE(c.triangle_count(), 100u);
      continue;
    }
    ASSERT_GE(c.children[0], 0);
    ASSERT_GE(c.children[1], 0);
    EXPECT_NE(c.children[0], c.children[1]);
    for (int k : c.children) {
      EXPECT_EQ(h.clusters[static_cast<std::size_t>(k)].parent, static_cast<int>(i));
      EXPECT_EQ(h.clusters[static_cast<std::size_t>(k)].depth, c.depth + 1);
      // Monotonic errors (sec. 3.5.1) and deformation levels (max over vertices).
      EXPECT_GE(c.error, h.clusters[static_cast<std::size_t>(k)].error);
      EXPECT_GE(c.deformation_level, h.clusters[static_cast<std::size_t>(k)].deformation_level);
    }
  }
  EXPECT_EQ(roots, 1);
  EXPECT_EQ(h.clusters[static_cast<std::size_t>(h.root)].parent, -1);
  EXPECT_EQ(leaves, h.stats.leaf_clusters);
  EXPECT_EQ(h.clusters.size(), 2 * leaves - 1);  // a full binary tree
  EXPECT_EQ(h.stats.clusters, h.clusters.size());
  EXPECT_EQ(h.stats.base_triangles, arm.triangle_count());
  EXPECT_EQ(h.stats.stored_triangles, h.indices.size() / 3);
  EXPECT_GT(h.clusters[static_cast<std::size_t>(h.root)].error, 0.f);
  // Balanced enough: matching rounds keep the depth near log2(leaves).
  int depth = 0;
  for (const Cluster& c : h.clusters) depth = std::max(depth, c.depth);
  EXPECT_LE(depth, 3 * static_cast<int>(std::ceil(std::log2(static_cast<double>(leaves)))) + 2);
}

TEST_P(ArmHierarchy, LeavesHoldTheBaseMeshExactlyOnce) {
  std::multiset<std::array<std::uint32_t, 3>> base, in_leaves;
  for (std::size_t t = 0; t < arm.triangle_count(); ++t)
    base.insert({arm.indices[3 * t], arm.indices[3 * t + 1], arm.indices[3 * t + 2]});
  for (std::size_t i = 0; i < h.clusters.size(); ++i) {
    if (!h.clusters[i].is_leaf()) continue;
    const auto tris = triangles_of(h, i);
    for (std::size_t k = 0; k < tris.size(); k += 3) in_leaves.insert({tris[k], tris[k + 1], tris[k + 2]});
  }
  EXPECT_EQ(base, in_leaves);
}

TEST_P(ArmHierarchy, ParentsHaveHalfTheirChildrensTriangles) {
  std::size_t short_of_half = 0, parents = 0;
  for (std::size_t i = 0; i < h.clusters.size(); ++i) {
    const Cluster& c = h.clusters[i];
    if (c.is_leaf()) continue;
    ++parents;
    const std::uint32_t children = h.clusters[static_cast<std::size_t>(c.children[0])].triangle_count() +
                                   h.clusters[static_cast<std::size_t>(c.children[1])].triangle_count();
    EXPECT_LE(c.triangle_count(), children);
    EXPECT_GT(c.triangle_count(), 0u);
    if (c.triangle_count() > children / 2) ++short_of_half;
  }
  EXPECT_EQ(short_of_half, h.stats.clusters_short_of_half);
  std::printf("[ arm %s ] %zu leaves, %zu of %zu parents short of half, stored/base triangles %.2f, root error %.4f\n",
              GetParam() == LeafClustering::octree ? "octree" : "error-aware", h.stats.leaf_clusters, short_of_half,
              parents, double(h.stats.stored_triangles) / double(h.stats.base_triangles),
              double(h.clusters[static_cast<std::size_t>(h.root)].error));
  // The root has no locked border: it always reaches half.
  const Cluster& root = h.clusters[static_cast<std::size_t>(h.root)];
  EXPECT_LE(root.triangle_count(), (h.clusters[static_cast<std::size_t>(root.children[0])].triangle_count() +
                                    h.clusters[static_cast<std::size_t>(root.children[1])].triangle_count()) / 2);
}

TEST_P(ArmHierarchy, VerticesSharedWithTheRestOfTheMeshStayReferenced) {
  // Locked vertices (sec. 3.4.3): a vertex of a parent's region that original triangles outside
  // the region also use must survive the parent's simplification, or neighbours would crack.
  const auto below = leaves_below(h);
  std::vector<std::set<int>> vertex_leaves(arm.vertex_count());
  for (std::size_t i = 0; i < h.clusters.size(); ++i) {
    if (!h.clusters[i].is_leaf()) continue;
    for (std::uint32_t v : triangles_of(h, i)) vertex_leaves[v].insert(static_cast<int>(i));
  }
  std::size_t checked = 0;
  for (std::size_t p = 0; p < h.clusters.size(); ++p) {
    const Cluster& c = h.clusters[p];
    if (c.is_leaf()) continue;
    const std::set<int> region(below[p].begin(), below[p].end());
    const auto own = triangles_of(h, p);
    const std::set<std::uint32_t> kept(own.begin(), own.end());
    for (int k : c.children)
      for (std::uint32_t v : triangles_of(h, static_cast<std::size_t>(k))) {
        const bool shared = std::any_of(vertex_leaves[v].begin(), vertex_leaves[v].end(),
                                        [&](int leaf) { return !region.count(leaf); });
        if (!shared) continue;
        ++checked;
        EXPECT_TRUE(kept.count(v)) << "cluster " << p << " dropped border vertex " << v;
      }
  }
  EXPECT_GT(checked, 0u);
}

TEST_P(ArmHierarchy, RandomCutsAreCrackFree) {
  // Any antichain covering the leaves is a valid cut; with locked borders the cut's triangles
  // form a closed surface except along the mesh's own open ends (the tube's two end rings).
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> base_edges;
  auto edge = [](std::uint32_t a, std::uint32_t b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  for (std::size_t t = 0; t < arm.triangle_count(); ++t)
    for (std::size_t k = 0; k < 3; ++k) ++base_edges[edge(arm.indices[3 * t + k], arm.indices[3 * t + (k + 1) % 3])];
  std::set<std::uint32_t> border;
  for (const auto& [e, n] : base_edges)
    if (n == 1) border.insert({e.first, e.second});
  ASSERT_FALSE(border.empty());

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 100; ++trial) {
    const double stop = unit(rng);
    std::vector<int> cut, stack{h.root};
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      const Cluster& cl = h.clusters[static_cast<std::size_t>(c)];
      if (cl.is_leaf() || unit(rng) < stop) {
        cut.push_back(c);
      } else {
        stack.insert(stack.end(), cl.children.begin(), cl.children.end());
      }
    }
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
    for (int c : cut) {
      const auto tris = triangles_of(h, static_cast<std::size_t>(c));
      for (std::size_t t = 0; t < tris.size(); t += 3)
        for (std::size_t k = 0; k < 3; ++k) ++uses[edge(tris[t + k], tris[t + (k + 1) % 3])];
    }
    for (const auto& [e, n] : uses) {
      EXPECT_LE(n, 2) << "trial " << trial;
      if (n == 1) {
        EXPECT_TRUE(border.count(e.first) && border.count(e.second))
            << "trial " << trial << ": open edge " << e.first << "-" << e.second << " away from the mesh border";
      }
    }
  }
}

TEST_P(ArmHierarchy, BoundsHoldEveryPoseAndNestChildren) {
  std::vector<std::vector<Vec3>> posed;
  for (const Pose& pose : arm.animations[0].poses) {
    posed.emplace_back();
    skin_positions(arm, pose, posed.back());
  }
  for (std::size_t i = 0; i < h.clusters.size(); ++i) {
    const Cluster& c = h.clusters[i];
    for (std::uint32_t v : triangles_of(h, i)) {
      for (const auto& x : posed) ASSERT_LT(c.bounds.exteriorDistance(x[v]), 1e-5f) << "cluster " << i;
    }
    if (c.is_leaf()) continue;
    for (int k : c.children) EXPECT_TRUE(c.bounds.contains(h.clusters[static_cast<std::size_t>(k)].bounds));
  }
}

INSTANTIATE_TEST_SUITE_P(Clustering, ArmHierarchy, ::testing::Values(LeafClustering::error_aware, LeafClustering::octree));

TEST(HierarchyBuild, PoseAwareErrorsSeeTheBend) {
  ArmSpec spec;
  spec.shape = ArmShape::strip;
  spec.around = 2;  // a ribbon of 80 triangles: lines across it stay straight when it bends, so
                    // with more vertices across, collapses across it would be free in every pose
  const SkinnedModel strip = make_arm(spec);  // flat in the straight pose, bent in the others
  HierarchyOptions o;
  o.max_leaf_triangles = 10;  // the root (about 10 triangles) must then collapse across the elbow
  const ClusterHierarchy straight = build_hierarchy(strip, o, {{0}});
  const ClusterHierarchy bent = build_hierarchy(strip, o, all_poses(strip));
  const float straight_root = straight.clusters[static_cast<std::size_t>(straight.root)].error;
  const float bent_root = bent.clusters[static_cast<std::size_t>(bent.root)].error;
  std::printf("[ strip ] root error straight pose only %.6f, all poses %.6f\n", double(straight_root), double(bent_root));
  EXPECT_LT(straight_root, 1e-4f);
  EXPECT_GT(bent_root, 0.01f);
  // Clusters that do not deform stay flat in every pose, so their error is ~0 (error-aware
  // clustering keeps them apart from the elbow).
  std::size_t rigid_parents = 0;
  for (const Cluster& c : bent.clusters)
    if (!c.is_leaf() && c.deformation_level < 1e-5f) {
      ++rigid_parents;
      EXPECT_LT(c.error, 1e-4f);
    }
  EXPECT_GT(rigid_parents, 0u);
}

TEST(HierarchyBuild, StaticModelAndModelWithoutAnimation) {
  const SkinnedModel grid = test_models::make_static_grid(30, 3.f);
  ASSERT_TRUE(grid.is_static());
  const ClusterHierarchy h = build_hierarchy(grid, {}, {{0}});
  EXPECT_EQ(h.stats.leaf_clusters, 32u);
  for (const Cluster& c : h.clusters) EXPECT_LT(c.error, 1e-4f);  // a plane simplifies exactly
  EXPECT_EQ(h.stats.poses_per_animation, std::vector<std::size_t>{1});
  EXPECT_EQ(h.stats.representative_poses_per_animation, std::vector<std::size_t>{1});
  EXPECT_LT(h.clusters[static_cast<std::size_t>(h.root)].triangle_count(), 100u);

  SkinnedModel bare = grid;
  bare.animations.clear();
  const ClusterHierarchy b = build_hierarchy(bare, {}, {});
  EXPECT_EQ(b.stats.leaf_clusters, 32u);
}

TEST(HierarchyBuild, DisconnectedPartsMergeByDistanceAndStayBalanced) {
  // A grid with 60 separate triangles just outside its edges: every loose triangle has the grid
  // as its nearest neighbour, which must not turn the tree into a chain.
  SkinnedModel m = test_models::make_static_grid(30, 3.f);
  for (int i = 0; i < 60; ++i) {
    const float t = 3.f * static_cast<float>(i % 15) / 15.f;
    const int side = i / 15;
    const Vec3 base = side == 0 ? Vec3(t, 0, -0.05f) : side == 1 ? Vec3(t, 0, 3.05f) : side == 2 ? Vec3(-0.05f, 0, t) : Vec3(3.05f, 0, t);
    const auto first = static_cast<std::uint32_t>(m.positions.size());
    for (const Vec3& p : {base, Vec3(base + Vec3(0.02f, 0, 0)), Vec3(base + Vec3(0, 0, 0.02f))}) {
      m.positions.push_back(p);
      m.normals.emplace_back(0, 1, 0);
      m.colors.push_back({0, 0, 0, 255});
      m.joints.push_back({0, 0, 0, 0});
      m.weights.push_back({1, 0, 0, 0});
    }
    m.indices.insert(m.indices.end(), {first, first + 2, first + 1});
  }
  const ClusterHierarchy h = build_hierarchy(m, {}, {{0}});
  EXPECT_NO_THROW(validate_hierarchy(h, m.vertex_count()));
  EXPECT_EQ(h.stats.leaf_clusters, 32u + 60u);
  int depth = 0;
  for (const Cluster& c : h.clusters) depth = std::max(depth, c.depth);
  EXPECT_LE(depth, 2 * static_cast<int>(std::ceil(std::log2(static_cast<double>(h.stats.leaf_clusters)))));
  // Nothing is simplified twice over: stored triangles stay within a few times the base mesh.
  EXPECT_LT(h.stats.stored_triangles, 4 * h.stats.base_triangles);
}

TEST(HierarchyBuild, BadRepresentativePosesThrow) {
  const SkinnedModel arm = make_arm();
  EXPECT_THROW(build_hierarchy(arm, {}, {}), std::invalid_argument);           // one list per animation
  EXPECT_THROW(build_hierarchy(arm, {}, {{}}), std::invalid_argument);         // no pose at all
  EXPECT_THROW(build_hierarchy(arm, {}, {{0, 20}}), std::invalid_argument);    // out of range
  EXPECT_THROW(build_hierarchy(arm, {}, {{-1}}), std::invalid_argument);
  HierarchyOptions o;
  o.max_leaf_triangles = 0;
  EXPECT_THROW(build_hierarchy(arm, o, {{0}}), std::invalid_argument);
  LeafTriangles overlapping{{0, 1}, {1, 2}};
  EXPECT_THROW(build_hierarchy_from_leaves(arm, {}, {{0}}, overlapping), std::invalid_argument);
}


}  // namespace
}  // namespace tourmap::crowd
