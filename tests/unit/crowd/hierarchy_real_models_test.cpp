// The hierarchy on the real glTF characters (CesiumMan, Fox, Horse), with pose selection: shape
// checks, plus the numbers the report quotes (build time, leaves, storage, and triangles in the
// cut of error-aware vs octree clustering at PoE 0.5 on 1280x720; sec. 3.6). Timings are in
// build/bench/crowd_bench.

#include "crowd/gltf_loader.hpp"
#include "crowd/hierarchy_build.hpp"
#include "crowd/hierarchy_io.hpp"
#include "crowd/lod_cut.hpp"
#include "crowd/subdivide.hpp"
#include "crowd_test_models.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <map>

namespace tourmap::crowd {
namespace {

const char* method_name(LeafClustering m) { return m == LeafClustering::octree ? "octree" : "error-aware"; }

void expect_sound(const SkinnedModel& m, const ClusterHierarchy& h, int s) {
  EXPECT_NO_THROW(validate_hierarchy(h, m.vertex_count()));
  std::map<std::array<std::uint32_t, 3>, int> base;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) ++base[{m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]}];
  for (const Cluster& c : h.clusters) {
    if (!c.is_leaf()) continue;
    EXPECT_LE(c.triangle_count(), static_cast<std::uint32_t>(s));
    for (std::uint32_t i = c.first_index; i < c.first_index + c.index_count; i += 3)
      --base[{h.indices[i], h.indices[i + 1], h.indices[i + 2]}];
  }
  for (const auto& [tri, n] : base) EXPECT_EQ(n, 0);  // every base triangle in exactly one leaf
  for (const Cluster& c : h.clusters) {
    if (c.is_leaf()) continue;
    for (int k : c.children) EXPECT_GE(c.error, h.clusters[static_cast<std::size_t>(k)].error);
  }
}

void print_stats(const SkinnedModel& m, LeafClustering method, const ClusterHierarchy& h) {
  std::size_t poses = 0, reps = 0;
  for (std::size_t n : h.stats.poses_per_animation) poses += n;
  for (std::size_t n : h.stats.representative_poses_per_animation) reps += n;
  std::printf("[ %s %s ] %zu triangles, %zu/%zu representative poses; %zu leaves, %zu clusters, stored/base %.2f, "
              "%zu parents short of half; %.0f ms (poses %.0f, clustering %.0f, simplification %.0f, error %.0f); "
              "%.1f bytes/base triangle\n",
              m.name.c_str(), method_name(method), m.triangle_count(), reps, poses, h.stats.leaf_clusters, h.stats.clusters,
              double(h.stats.stored_triangles) / double(h.stats.base_triangles), h.stats.clusters_short_of_half,
              h.stats.total_ms, h.stats.pose_selection_ms, h.stats.clustering_ms, h.stats.simplification_ms, h.stats.error_ms,
              double(serialize_hierarchy(h).size()) / double(h.stats.base_triangles));
}

class HierarchyRealModel : public ::testing::TestWithParam<const char*> {};

TEST_P(HierarchyRealModel, BuildsSoundHierarchiesBothWays) {
  const SkinnedModel m = load_skinned_model(tourmap::test::data_file(GetParam()));
  for (LeafClustering method : {LeafClustering::error_aware, LeafClustering::octree}) {
    HierarchyOptions o;
    o.clustering = method;
    const ClusterHierarchy h = build_vdr_hierarchy(m, o);
    expect_sound(m, h, o.max_leaf_triangles);
    ASSERT_EQ(h.stats.representative_poses_per_animation.size(), m.animations.size());
    for (std::size_t a = 0; a < m.animations.size(); ++a) {
      EXPECT_GE(h.stats.representative_poses_per_animation[a], 1u);
      EXPECT_LE(h.stats.representative_poses_per_animation[a], h.stats.poses_per_animation[a]);
    }
    print_stats(m, method, h);
  }
}

INSTANTIATE_TEST_SUITE_P(Models, HierarchyRealModel,
                         ::testing::Values("models/humans/CesiumMan.glb", "models/animals/Fox.glb",
                                           "models/animals/Horse.glb"));

TEST(HierarchyRealModelCut, CesiumManErrorAwareVsOctree) {
  // Triangles in the LOD cut at the same view: the paper reports ~50% fewer with error-aware
  // clustering. Printed, not asserted: it depends on the model (see the report).
  const SkinnedModel m = load_skinned_model(tourmap::test::data_file("models/humans/CesiumMan.glb"));
  std::map<LeafClustering, ClusterHierarchy> h;
  for (LeafClustering method : {LeafClustering::error_aware, LeafClustering::octree}) {
    HierarchyOptions o;
    o.clustering = method;
    h[method] = build_vdr_hierarchy(m, o);
  }
  const Box3 box = h[LeafClustering::error_aware].clusters[static_cast<std::size_t>(h[LeafClustering::error_aware].root)].bounds;
  for (float distance : {2.f, 5.f, 10.f, 20.f, 40.f, 80.f}) {
    const CameraView view = test_models::look_at(box.center() + Vec3(0, 0, distance), box.center(), 1280, 720,
                                                 1.0471976f, 0.1f, 1000.f);
    std::map<LeafClustering, CutStats> stats;
    for (auto& [method, hierarchy] : h) {
      std::vector<int> cut;
      lod_cut(hierarchy, Affine::Identity(), view, 0.5f, cut, stats[method]);
      EXPECT_GT(stats[method].triangles, 0u);
      EXPECT_LE(stats[method].triangles, m.triangle_count());
    }
    std::printf("[ CesiumMan cut, PoE 0.5, 1280x720, %4.0f m ] error-aware %zu triangles in %zu clusters, "
                "octree %zu triangles in %zu clusters (ratio %.2f)\n",
                double(distance), stats[LeafClustering::error_aware].triangles, stats[LeafClustering::error_aware].drawn,
                stats[LeafClustering::octree].triangles, stats[LeafClustering::octree].drawn,
                double(stats[LeafClustering::error_aware].triangles) / double(stats[LeafClustering::octree].triangles));
  }
}

}  // namespace
}  // namespace tourmap::crowd
