#include "crowd/lod_cut.hpp"

#include "crowd/cut_instances.hpp"
#include "crowd/hierarchy_build.hpp"
#include "crowd_test_models.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

namespace tourmap::crowd {
namespace {

// Brute force, written from the rule instead of the walk (sec. 3.5.1): a cluster is in the cut
// iff (it is a leaf or its error sphere projects to <= PoE px), no proper ancestor passes that
// rule, and neither it nor any ancestor is outside the frustum. The frustum test takes the eight
// world-space corners of the cluster's box as the instance places it (an oriented box): outside
// when all eight are behind one plane. The distance is the eye's (moved into model space)
// distance to the model-space box, times the instance's scale.
struct BruteCut {
  const ClusterHierarchy& h;
  const Affine& world;
  const CameraView& view;
  float poe;

  std::array<Vec3, 8> world_corners(const Box3& b) const {
    std::array<Vec3, 8> out;
    for (int k = 0; k < 8; ++k) out[static_cast<std::size_t>(k)] = world * b.corner(static_cast<Box3::CornerType>(k));
    return out;
  }
  bool culled(int id) const {
    const auto corners = world_corners(h.clusters[static_cast<std::size_t>(id)].bounds);
    const Eigen::Matrix4f& m = view.view_proj;
    const std::array<Eigen::Vector4f, 6> planes = {
        Eigen::Vector4f(m.row(3) + m.row(0)), Eigen::Vector4f(m.row(3) - m.row(0)), Eigen::Vector4f(m.row(3) + m.row(1)),
        Eigen::Vector4f(m.row(3) - m.row(1)), Eigen::Vector4f(m.row(3) + m.row(2)), Eigen::Vector4f(m.row(3) - m.row(2))};
    for (const auto& p : planes)
      if (std::all_of(corners.begin(), corners.end(), [&](const Vec3& c) { return p.head<3>().dot(c) + p.w() < 0; }))
        return true;
    return false;
  }
  bool fine_enough(int id) const {
    const Cluster& c = h.clusters[static_cast<std::size_t>(id)];
    if (poe <= 0) return false;
    const float scale = world.linear().col(0).norm();
    const float dist = c.bounds.exteriorDistance(world.inverse() * view.eye) * scale;
    return projected_diameter_px(c.error * scale, dist, view) <= poe;
  }
  std::vector<int> cut() const {
    std::vector<int> out;
    for (std::size_t i = 0; i < h.clusters.size(); ++i) {
      const int id = static_cast<int>(i);
      if (!(h.clusters[i].is_leaf() || fine_enough(id)) || culled(id)) continue;
      bool ok = true;
      for (int a = h.clusters[i].parent; a >= 0 && ok; a = h.clusters[static_cast<std::size_t>(a)].parent)
        ok = !fine_enough(a) && !culled(a);
      if (ok) out.push_back(id);
    }
    return out;
  }
};

const SkinnedModel& arm() {
  static const SkinnedModel m = test_models::make_arm();
  return m;
}

const ClusterHierarchy& hierarchy(LeafClustering method) {
  static const ClusterHierarchy ea = [] {
    return build_hierarchy(arm(), {}, test_models::all_poses(arm()));
  }();
  static const ClusterHierarchy oc = [] {
    HierarchyOptions o;
    o.clustering = LeafClustering::octree;
    o.max_leaf_triangles = 40;
    return build_hierarchy(arm(), o, test_models::all_poses(arm()));
  }();
  return method == LeafClustering::octree ? oc : ea;
}

struct RandomView {
  Affine world;
  CameraView view;
  float poe;
};

RandomView random_view(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1, 1), pos(0, 1);
  const float scale = 0.5f + 2 * pos(rng);
  const Affine world = Eigen::Translation3f(3 * u(rng), 0.5f * u(rng), 3 * u(rng)) *
                       Eigen::AngleAxisf(3.14159f * u(rng), Vec3(u(rng), 1, u(rng)).normalized()) *
                       Eigen::Scaling(scale);
  // Near to far (0.5-60 m), sometimes looking away so part or all of the arm is culled.
  const float dist = 0.5f + 60 * pos(rng) * pos(rng);
  const Vec3 eye = Vec3(u(rng), 0.3f * u(rng), u(rng)).normalized() * dist;
  const Vec3 target = world * Vec3(1, 0, 0) + Vec3(u(rng), u(rng), u(rng)) * (pos(rng) < 0.5f ? 6.f : 0.3f);
  const float fov = 0.3f + 1.2f * pos(rng);
  const std::array<float, 8> poes = {0.f, 0.1f, 0.25f, 0.5f, 1.f, 2.f, 5.f, 50.f};
  return {world, test_models::look_at(eye, target, 1280, 720, fov, 0.05f, 200.f),
          poes[static_cast<std::size_t>(rng() % poes.size())]};
}

class LodCutVsBruteForce : public ::testing::TestWithParam<LeafClustering> {};

TEST_P(LodCutVsBruteForce, SameClustersForRandomViews) {
  const ClusterHierarchy& h = hierarchy(GetParam());
  std::mt19937 rng(11);
  std::size_t partial = 0, empty = 0, coarse = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const RandomView rv = random_view(rng);
    std::vector<int> walk;
    CutStats stats;
    lod_cut(h, rv.world, rv.view, rv.poe, walk, stats);
    std::vector<int> brute = BruteCut{h, rv.world, rv.view, rv.poe}.cut();
    std::sort(walk.begin(), walk.end());
    ASSERT_EQ(walk, brute) << "trial " << trial << " poe " << rv.poe;
    std::size_t triangles = 0;
    for (int c : brute) triangles += h.clusters[static_cast<std::size_t>(c)].triangle_count();
    EXPECT_EQ(stats.triangles, triangles);
    EXPECT_EQ(stats.drawn, brute.size());
    if (brute.empty()) ++empty;
    if (stats.frustum_culled > 0 && !brute.empty()) ++partial;
    if (std::any_of(brute.begin(), brute.end(), [&](int c) { return !h.clusters[static_cast<std::size_t>(c)].is_leaf(); })) ++coarse;
  }
  // The random views exercise every case.
  EXPECT_GT(empty, 10u);
  EXPECT_GT(partial, 10u);
  EXPECT_GT(coarse, 50u);
}

TEST_P(LodCutVsBruteForce, CutCoversEveryLeafOnceOrCullsIt) {
  // No overlap, no gap: each leaf is below exactly one drawn cluster, unless the walk from the
  // root meets a cluster outside the frustum before it meets a drawn one (then below none).
  const ClusterHierarchy& h = hierarchy(GetParam());
  std::mt19937 rng(5);
  std::size_t culled_leaves = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const RandomView rv = random_view(rng);
    std::vector<int> cut;
    CutStats stats;
    lod_cut(h, rv.world, rv.view, rv.poe, cut, stats);
    const BruteCut brute{h, rv.world, rv.view, rv.poe};
    std::vector<int> drawn(h.clusters.size(), 0);
    for (int c : cut) ++drawn[static_cast<std::size_t>(c)];
    for (std::size_t i = 0; i < h.clusters.size(); ++i) {
      if (!h.clusters[i].is_leaf()) continue;
      std::vector<int> path;  // leaf to root
      for (int a = static_cast<int>(i); a >= 0; a = h.clusters[static_cast<std::size_t>(a)].parent) path.push_back(a);
      int covering = 0;
      bool culled_first = false;
      for (auto it = path.rbegin(); it != path.rend(); ++it) {  // root to leaf
        covering += drawn[static_cast<std::size_t>(*it)];
        if (covering == 0 && brute.culled(*it)) culled_first = true;
      }
      EXPECT_EQ(covering, culled_first ? 0 : 1) << "trial " << trial << " leaf " << i;
      culled_leaves += culled_first;
    }
  }
  EXPECT_GT(culled_leaves, 0u);
}

TEST(LodCut, ChildStickingOutOfItsParentIsCulled) {
  // A child's box need not lie inside its parent's (a parent's vertices are a subset of its
  // children's; build_hierarchy widens a parent's box over its children's, but a hierarchy read
  // or made elsewhere need not): here the root's box is wholly inside the frustum and its right
  // child's wholly outside, so a "root inside => skip the plane tests below" shortcut would draw
  // that child.
  ClusterHierarchy h;
  h.clusters.resize(3);
  h.root = 0;
  h.clusters[0].children = {1, 2};
  h.clusters[0].error = 1;
  h.clusters[0].bounds = Box3(Vec3(0.3f, 0.3f, 0), Vec3(0.7f, 0.7f, 1));
  h.clusters[1].parent = h.clusters[2].parent = 0;
  h.clusters[1].bounds = h.clusters[0].bounds;
  h.clusters[2].bounds = Box3(Vec3(2, 0.3f, 0), Vec3(3, 0.7f, 1));
  // Looking down -z from 10 m with a narrow view: x spans about [-0.4, 1.4] at z = 1.
  const CameraView view = test_models::look_at(Vec3(0.5f, 0.5f, 10), Vec3(0.5f, 0.5f, 0), 1280, 720, 0.112f, 0.05f, 200.f);
  const Affine world = Affine::Identity();
  std::vector<int> cut;
  CutStats stats;
  lod_cut(h, world, view, 0.5f, cut, stats);
  EXPECT_EQ(cut, std::vector<int>{1});
  EXPECT_EQ(stats.frustum_culled, 1u);
  EXPECT_EQ(cut, (BruteCut{h, world, view, 0.5f}.cut()));
  EXPECT_TRUE((BruteCut{h, world, view, 0.5f}.culled(2)));
}

// Many instances of both hierarchies through cut_instances, on this thread and on two: the same
// cuts, ranges and stats, and each instance's range is its brute-force cut.
TEST(CutInstances, EqualsPerInstanceBruteForceInInstanceOrder) {
  const std::array<const ClusterHierarchy*, 2> hs = {&hierarchy(LeafClustering::error_aware),
                                                     &hierarchy(LeafClustering::octree)};
  const std::array<CutTree, 2> trees = {build_cut_tree(*hs[0]), build_cut_tree(*hs[1])};
  util::ForkJoin pool(2);
  CutWorkspace one_ws, two_ws;
  std::mt19937 rng(23);
  std::size_t empty = 0, partial = 0, whole = 0, multi_chunk_frames = 0;
  for (int frame = 0; frame < 40; ++frame) {
    const RandomView camera = random_view(rng);
    const std::size_t n = 1 + rng() % 300;
    multi_chunk_frames += n > kCutChunk;
    std::vector<Affine> worlds(n);
    std::vector<int> model(n);
    std::vector<CutInstance> instances(n);
    for (std::size_t i = 0; i < n; ++i) {
      worlds[i] = random_view(rng).world;
      model[i] = static_cast<int>(rng() % 2);
      instances[i] = {&trees[static_cast<std::size_t>(model[i])], &worlds[i]};
    }
    std::vector<int> cut1, cut2;
    std::vector<std::size_t> begin1, begin2;
    CutStats s1, s2;
    cut_instances(instances, camera.view, camera.poe, nullptr, one_ws, cut1, begin1, s1);
    cut_instances(instances, camera.view, camera.poe, &pool, two_ws, cut2, begin2, s2);
    ASSERT_EQ(cut1, cut2) << "frame " << frame;
    ASSERT_EQ(begin1, begin2) << "frame " << frame;
    EXPECT_EQ(s1.visited, s2.visited);
    EXPECT_EQ(s1.drawn, s2.drawn);
    EXPECT_EQ(s1.frustum_culled, s2.frustum_culled);
    EXPECT_EQ(s1.triangles, s2.triangles);
    ASSERT_EQ(begin1.size(), n + 1);
    EXPECT_EQ(begin1.back(), cut1.size());
    std::size_t triangles = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const ClusterHierarchy& h = *hs[static_cast<std::size_t>(model[i])];
      std::vector<int> mine(cut1.begin() + static_cast<std::ptrdiff_t>(begin1[i]),
                            cut1.begin() + static_cast<std::ptrdiff_t>(begin1[i + 1]));
      std::sort(mine.begin(), mine.end());
      const std::vector<int> brute = BruteCut{h, worlds[i], camera.view, camera.poe}.cut();
      ASSERT_EQ(mine, brute) << "frame " << frame << " instance " << i;
      for (int c : brute) triangles += h.clusters[static_cast<std::size_t>(c)].triangle_count();
      std::size_t leaves = 0;
      for (const Cluster& c : h.clusters) leaves += c.is_leaf();
      if (brute.empty()) ++empty;
      else if (camera.poe <= 0 && brute.size() < leaves) ++partial;
      else if (camera.poe <= 0) ++whole;
    }
    EXPECT_EQ(s1.triangles, triangles);
    EXPECT_EQ(s1.drawn, cut1.size());
  }
  // Culled, partly culled and whole instances, and frames split over several chunks.
  EXPECT_GT(empty, 100u);
  EXPECT_GT(partial, 5u);
  EXPECT_GT(whole, 5u);
  EXPECT_GT(multi_chunk_frames, 30u);
}

INSTANTIATE_TEST_SUITE_P(Clustering, LodCutVsBruteForce,
                         ::testing::Values(LeafClustering::error_aware, LeafClustering::octree));

}  // namespace
}  // namespace tourmap::crowd
