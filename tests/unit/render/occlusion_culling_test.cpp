// VDR+OC (sec. 3.5.2) on a synthetic occluder scene: a wall (static model) between the camera
// and a grid of dynamic boxes, with two boxes beside the wall.

#include "render/camera.hpp"
#include "render/crowd_renderer.hpp"
#include "render/egl_context.hpp"
#include "render_test_scenes.hpp"

#include <gtest/gtest.h>

namespace tourmap::render {
namespace {

using test::Rgba;

constexpr int kW = 160, kH = 120;

bool reddish(const Rgba& p) { return p[0] > 2 * p[1] + 10 && p[0] > 2 * p[2] + 10; }

struct WallScene {
  explicit WallScene(CrowdRenderer& renderer) {
    wall = renderer.add_model(test::box_model({4, 2, 0.2f}, {150, 150, 160, 255}, 6), test::test_hierarchy(
                                  test::box_model({4, 2, 0.2f}, {150, 150, 160, 255}, 6), 2));
    const crowd::SkinnedModel box = test::box_model({0.4f, 0.4f, 0.4f}, {40, 200, 60, 255}, 4, 2);
    object = renderer.add_model(box, test::test_hierarchy(box, 2));
    const crowd::SkinnedModel red = test::box_model({0.4f, 0.4f, 0.4f}, {220, 40, 40, 255}, 4, 2);
    side = renderer.add_model(red, test::test_hierarchy(red, 2));
  }

  std::vector<InstanceState> instances() const {
    std::vector<InstanceState> out;
    const auto put = [&](int model, const crowd::Vec3& p) {
      InstanceState s;
      s.model = model;
      s.world = Eigen::Translation3f(p) * Eigen::Matrix3f::Identity();
      out.push_back(s);
    };
    put(wall, {0, 2, 0});
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 5; ++col)
        put(object, {-3.f + 1.5f * static_cast<float>(col), 1, -3.f - 2.f * static_cast<float>(row)});
    put(side, {-7, 1, -3});
    put(side, {7, 1, -3});
    return out;
  }

  int wall = 0, object = 0, side = 0;
  static constexpr std::size_t kGrid = 20;
};

FrameRequest request(const crowd::Vec3& eye, const crowd::Vec3& target, RenderMode mode, const WallScene& scene) {
  FrameRequest r;
  r.camera = make_camera_view(eye, target, {0, 1, 0}, 1.0f, kW, kH);
  r.instances = scene.instances();
  r.mode = mode;
  r.poe = 0.5f;
  r.ground = true;
  return r;
}

TEST(OcclusionCulling, WallHidesTheGridAndTheImageMatchesVdr) {
  CrowdRenderer renderer(test::shared_context());
  const WallScene scene(renderer);
  std::vector<std::uint8_t> vdr_image, oc_image;
  FrameStats vdr, first, second;
  FrameRequest r = request({0, 1.6f, 10}, {0, 1.6f, 0}, RenderMode::vdr, scene);
  renderer.render(r, vdr_image, vdr);
  EXPECT_EQ(vdr.instances_visible, 23u);
  EXPECT_EQ(vdr.occluded, 0u);

  r.mode = RenderMode::vdr_oc;
  renderer.render(r, oc_image, first);
  EXPECT_TRUE(first.pvs_reset);
  EXPECT_GT(first.occluded, 0u);
  renderer.render(r, oc_image, second);
  EXPECT_FALSE(second.pvs_reset);
  EXPECT_GT(second.occluded, 0u);
  EXPECT_LT(second.triangles, vdr.triangles);
  EXPECT_EQ(second.instances_visible, 3u);  // the wall and the two boxes beside it
  // The side boxes are in the PVS now; only the hidden grid is queried, one query per instance.
  EXPECT_LE(second.occlusion_queries, WallScene::kGrid);
  EXPECT_GT(second.occlusion_queries, 0u);
  EXPECT_EQ(test::differing_pixels(vdr_image, oc_image), 0u);
  const auto left = test::project_to_pixel(r.camera, {-7, 1, -2.6f});
  const auto right = test::project_to_pixel(r.camera, {7, 1, -2.6f});
  EXPECT_TRUE(reddish(test::pixel(oc_image, kW, kH, left[0], left[1])));
  EXPECT_TRUE(reddish(test::pixel(oc_image, kW, kH, right[0], right[1])));
  std::printf("vdr %zu tris %zu clusters; vdr_oc frame 1: %zu tris %zu occluded %zu queries; frame 2: %zu tris %zu "
              "occluded %zu queries\n", vdr.triangles, vdr.clusters_drawn, first.triangles, first.occluded,
              first.occlusion_queries, second.triangles, second.occluded, second.occlusion_queries);
}

TEST(OcclusionCulling, StaysConservativeWhenTheCameraRevealsHiddenObjectsWithoutAReset) {
  RendererOptions options;
  options.coherence.jump_distance_m = 1000;  // keep the PVS across the move below
  options.coherence.jump_angle_rad = 4;
  CrowdRenderer renderer(test::shared_context(), options);
  const WallScene scene(renderer);
  std::vector<std::uint8_t> vdr_image, oc_image;
  FrameStats vdr, oc;
  FrameRequest r = request({0, 1.6f, 10}, {0, 1.6f, 0}, RenderMode::vdr_oc, scene);
  renderer.render(r, oc_image, oc);
  renderer.render(r, oc_image, oc);
  ASSERT_EQ(oc.instances_visible, 3u);

  // Step past the wall's end: the grid comes into view, nothing of it is in the PVS.
  r = request({9, 1.6f, 4}, {0, 1, -6}, RenderMode::vdr_oc, scene);
  renderer.render(r, oc_image, oc);
  EXPECT_FALSE(oc.pvs_reset);
  EXPECT_GT(oc.instances_visible, 3u + 5u);
  r.mode = RenderMode::vdr;
  renderer.render(r, vdr_image, vdr);
  EXPECT_EQ(test::differing_pixels(vdr_image, oc_image), 0u);
  EXPECT_LE(oc.triangles, vdr.triangles);
}

TEST(OcclusionCulling, ResetCoherenceEmptiesThePvs) {
  CrowdRenderer renderer(test::shared_context());
  const WallScene scene(renderer);
  std::vector<std::uint8_t> image;
  FrameStats stats;
  FrameRequest r = request({0, 1.6f, 10}, {0, 1.6f, 0}, RenderMode::vdr_oc, scene);
  renderer.render(r, image, stats);
  renderer.render(r, image, stats);
  EXPECT_FALSE(stats.pvs_reset);
  renderer.reset_coherence();
  renderer.render(r, image, stats);
  EXPECT_TRUE(stats.pvs_reset);
  // A vdr frame in between makes the next vdr_oc frame start afresh too.
  r.mode = RenderMode::vdr;
  renderer.render(r, image, stats);
  r.mode = RenderMode::vdr_oc;
  renderer.render(r, image, stats);
  EXPECT_TRUE(stats.pvs_reset);
}

TEST(OcclusionCulling, NearDynamicObjectsHideFarOnesRightAfterAReset) {
  // No static occluder: a wide dynamic box in front of 16 small ones. Right after a PVS reset the
  // depth buffer holds only the ground, so the far boxes can only be culled because the front-to-
  // back batches draw the near box before testing them.
  CrowdRenderer renderer(test::shared_context());
  const crowd::SkinnedModel screen = test::box_model({3, 2, 0.3f}, {150, 150, 160, 255}, 4, 2);
  const int screen_id = renderer.add_model(screen, test::test_hierarchy(screen, 2));
  const crowd::SkinnedModel box = test::box_model({0.4f, 0.4f, 0.4f}, {40, 200, 60, 255}, 4, 2);
  const int box_id = renderer.add_model(box, test::test_hierarchy(box, 2));
  FrameRequest r;
  r.camera = make_camera_view({0, 1.6f, 10}, {0, 1.6f, 0}, {0, 1, 0}, 1.0f, kW, kH);
  r.mode = RenderMode::vdr;
  const auto put = [&](int model, const crowd::Vec3& p) {
    InstanceState s;
    s.model = model;
    s.world = Eigen::Translation3f(p) * Eigen::Matrix3f::Identity();
    r.instances.push_back(s);
  };
  put(screen_id, {0, 2, 0});
  for (int k = 0; k < 16; ++k) put(box_id, {-1.5f + static_cast<float>(k % 4), 1, -3.f - 2.f * static_cast<float>(k / 4)});
  std::vector<std::uint8_t> vdr_image, oc_image;
  FrameStats vdr, oc;
  renderer.render(r, vdr_image, vdr);
  r.mode = RenderMode::vdr_oc;
  renderer.render(r, oc_image, oc);
  EXPECT_TRUE(oc.pvs_reset);
  EXPECT_GT(oc.occluded, 0u);
  EXPECT_EQ(oc.instances_visible, 1u);
  EXPECT_LT(oc.triangles, vdr.triangles);
  EXPECT_EQ(test::differing_pixels(vdr_image, oc_image), 0u);
}

}  // namespace
}  // namespace tourmap::render
