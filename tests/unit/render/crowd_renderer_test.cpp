#include "render/crowd_renderer.hpp"

#include "render/camera.hpp"
#include "render/egl_context.hpp"
#include "render_test_scenes.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace tourmap::render {
namespace {

using test::Rgba;

constexpr int kW = 160, kH = 120;
const Rgba kRed{220, 40, 40, 255};
const Rgba kGreen{40, 200, 60, 255};

bool is_sky(const Rgba& p) { return p[0] == kSkyRgb[0] && p[1] == kSkyRgb[1] && p[2] == kSkyRgb[2]; }
bool reddish(const Rgba& p) { return p[0] > 2 * p[1] + 10 && p[0] > 2 * p[2] + 10; }
bool bluish(const Rgba& p) { return p[2] > 2 * p[0] + 10 && p[2] > p[1] + 10; }
bool greenish(const Rgba& p) { return p[1] > 2 * p[0] + 10 && p[1] > 2 * p[2] + 10; }

FrameRequest request_at(const crowd::Vec3& eye, const crowd::Vec3& target, RenderMode mode = RenderMode::vdr) {
  FrameRequest r;
  r.camera = make_camera_view(eye, target, {0, 1, 0}, 1.0f, kW, kH);
  r.mode = mode;
  r.poe = 0.5f;
  r.ground = false;
  return r;
}

InstanceState placed(int model, const crowd::Vec3& position, int frame = 0) {
  InstanceState s;
  s.model = model;
  s.world = Eigen::Translation3f(position) * Eigen::Matrix3f::Identity();
  s.frame = frame;
  return s;
}

class CrowdRendererTest : public ::testing::Test {
 protected:
  CrowdRendererTest() : renderer_(test::shared_context()) {}

  int add(const crowd::SkinnedModel& m, int levels = 2) { return renderer_.add_model(m, test::test_hierarchy(m, levels)); }
  Rgba at(int x, int y_from_top) const { return test::pixel(image_, kW, kH, x, y_from_top); }
  Rgba at(const FrameRequest& r, const crowd::Vec3& world) const {
    const auto p = test::project_to_pixel(r.camera, world);
    return at(p[0], p[1]);
  }

  CrowdRenderer renderer_;
  std::vector<std::uint8_t> image_;
  FrameStats stats_;
};

TEST_F(CrowdRendererTest, StaticBoxCoversTheCentrePixelWithItsColour) {
  const int box = add(test::box_model({0.5f, 0.5f, 0.5f}, kRed));
  FrameRequest r = request_at({0, 1.5f, 4}, {0, 1, 0});
  r.instances = {placed(box, {0, 1, 0})};
  renderer_.render(r, image_, stats_);
  ASSERT_EQ(image_.size(), std::size_t{kW * kH * 4});
  EXPECT_TRUE(reddish(at(kW / 2, kH / 2)));
  EXPECT_TRUE(is_sky(at(2, 2)));
  EXPECT_TRUE(is_sky(at(kW - 3, kH - 3)));
  EXPECT_EQ(stats_.instances_visible, 1u);
  EXPECT_GT(stats_.triangles, 0u);

  // With the ground plane the bottom rows show ground (not sky) and the box still covers the centre.
  r.ground = true;
  renderer_.render(r, image_, stats_);
  EXPECT_TRUE(reddish(at(kW / 2, kH / 2)));
  EXPECT_FALSE(is_sky(at(kW / 2, kH - 2)));
  EXPECT_NE(at(kW / 2, kH - 2), at(kW / 2, 1));  // ground differs from the sky above
}

TEST_F(CrowdRendererTest, SkinnedBarBendsWhereCpuSkinningPutsIt) {
  const crowd::SkinnedModel bar = test::bar_model(kGreen);
  const int id = add(bar, 1);
  FrameRequest r = request_at({1, 0.5f, 3.5f}, {1, 0.5f, 0});
  // Two front-face vertices of the segment at x = 1.75; in the bent pose they sit around (1, 0.75, 0.1).
  std::vector<std::size_t> tip;
  for (std::size_t v = 0; v < bar.positions.size(); ++v)
    if (std::abs(bar.positions[v].x() - 1.75f) < 1e-4f && std::abs(bar.positions[v].z() - 0.1f) < 1e-4f &&
        bar.normals[v].z() > 0.5f)
      tip.push_back(v);
  ASSERT_EQ(tip.size(), 2u);
  crowd::Vec3 bent_tip = crowd::Vec3::Zero();
  for (std::size_t v : tip) bent_tip += test::skinned_position(bar, bar.animations[0].poses[1], v) / 2.f;
  ASSERT_NEAR(bent_tip.y(), 0.75f, 1e-4f);

  r.instances = {placed(id, {0, 0, 0}, 0)};
  renderer_.render(r, image_, stats_);
  const std::vector<std::uint8_t> straight = image_;
  EXPECT_TRUE(is_sky(at(r, bent_tip)));
  EXPECT_TRUE(greenish(at(r, {1.75f, 0, 0.1f})));

  r.instances = {placed(id, {0, 0, 0}, 1)};
  renderer_.render(r, image_, stats_);
  EXPECT_TRUE(greenish(at(r, bent_tip)));
  EXPECT_TRUE(is_sky(at(r, {1.75f, 0, 0.1f})));
  EXPECT_GT(test::differing_pixels(straight, image_), 100u);
}

TEST_F(CrowdRendererTest, InstancesInARowAllAppearWithOneCommandPerCluster) {
  const int box = add(test::box_model({0.4f, 0.4f, 0.4f}, kRed));
  FrameRequest r = request_at({0, 1, 9}, {0, 1, 0}, RenderMode::no_lod);
  for (int i = 0; i < 5; ++i) r.instances.push_back(placed(box, {-4.f + 2.f * static_cast<float>(i), 1, 0}));
  r.instances[4].tint = 0.6f;  // a blue-green hue mixed in
  renderer_.render(r, image_, stats_);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(reddish(at(r, {-4.f + 2.f * static_cast<float>(i), 1, 0.4f}))) << i;
  const Rgba tinted = at(r, {4, 1, 0.4f});
  EXPECT_FALSE(is_sky(tinted));
  EXPECT_FALSE(reddish(tinted));
  EXPECT_TRUE(is_sky(at(r, {-3, 1, 0})));  // the gaps between the boxes
  EXPECT_EQ(stats_.instances_visible, 5u);
  EXPECT_EQ(stats_.clusters_drawn, 5u * 4u);  // 4 leaves each
  // 20 (instance, cluster) pairs: the 4 leaves are neighbours in the index buffer, drawn for the same
  // 5 instances, so they make one command with instanceCount 5.
  EXPECT_EQ(stats_.draw_commands, 1u);
  EXPECT_EQ(stats_.triangles, 5u * 12u * 16u);
}

TEST_F(CrowdRendererTest, InstancesBehindTheCameraAreCulledAndChangeNothing) {
  const int box = add(test::box_model({0.4f, 0.4f, 0.4f}, kRed));
  FrameRequest r = request_at({0, 1, 5}, {0, 1, 0});
  for (int i = 0; i < 3; ++i) r.instances.push_back(placed(box, {-2.f + 2.f * static_cast<float>(i), 1, 0}));
  renderer_.render(r, image_, stats_);
  const std::vector<std::uint8_t> front_only = image_;
  const FrameStats front_stats = stats_;
  for (int i = 0; i < 3; ++i) r.instances.push_back(placed(box, {-2.f + 2.f * static_cast<float>(i), 1, 8}));
  renderer_.render(r, image_, stats_);
  EXPECT_EQ(stats_.frustum_culled, front_stats.frustum_culled + 3);  // each root culled whole
  EXPECT_EQ(stats_.instances_visible, 3u);
  EXPECT_EQ(stats_.triangles, front_stats.triangles);
  EXPECT_EQ(test::differing_pixels(front_only, image_), 0u);
}

TEST_F(CrowdRendererTest, NoLodEqualsVdrAsPoeGoesToZeroAndVdrSimplifiesFarAway) {
  const int box = add(test::box_model({0.5f, 0.5f, 0.5f}, kRed), 3);
  FrameRequest r = request_at({0, 1.5f, 4}, {0, 1, 0}, RenderMode::no_lod);
  r.instances = {placed(box, {0, 1, 0}), placed(box, {1.5f, 1, -3})};
  renderer_.render(r, image_, stats_);
  const std::vector<std::uint8_t> no_lod = image_;
  const FrameStats no_lod_stats = stats_;
  r.mode = RenderMode::vdr;
  r.poe = 1e-6f;
  renderer_.render(r, image_, stats_);
  EXPECT_EQ(test::differing_pixels(no_lod, image_), 0u);
  EXPECT_EQ(stats_.triangles, no_lod_stats.triangles);
  r.poe = 40.f;
  renderer_.render(r, image_, stats_);
  EXPECT_LT(stats_.triangles, no_lod_stats.triangles);
  EXPECT_LT(stats_.clusters_drawn, no_lod_stats.clusters_drawn);
}

TEST_F(CrowdRendererTest, HeatmapIsRedAtLeavesAndBlueAtTheRoot) {
  const int box = add(test::box_model({0.5f, 0.5f, 0.5f}, kGreen), 3);
  FrameRequest r = request_at({0, 1.5f, 4}, {0, 1, 0}, RenderMode::vdr);
  r.instances = {placed(box, {0, 1, 0})};
  r.heatmap = true;
  r.poe = 1e-6f;
  renderer_.render(r, image_, stats_);
  EXPECT_TRUE(reddish(at(kW / 2, kH / 2)));
  r.poe = 1e6f;
  renderer_.render(r, image_, stats_);
  EXPECT_EQ(stats_.clusters_drawn, 1u);
  EXPECT_TRUE(bluish(at(kW / 2, kH / 2)));
}

TEST_F(CrowdRendererTest, OutputSizeFollowsTheRequestWithinTheCap) {
  const int box = add(test::box_model({0.5f, 0.5f, 0.5f}, kRed));
  FrameRequest r = request_at({0, 1.5f, 4}, {0, 1, 0});
  r.instances = {placed(box, {0, 1, 0})};
  r.camera = make_camera_view({0, 1.5f, 4}, {0, 1, 0}, {0, 1, 0}, 1.0f, 64, 48);
  renderer_.render(r, image_, stats_);
  EXPECT_EQ(image_.size(), std::size_t{64 * 48 * 4});
  for (auto [w, h] : {std::pair{0, 48}, {64, 0}, {1921, 100}, {100, 1081}, {-5, 5}}) {
    r.camera.width = w;
    r.camera.height = h;
    EXPECT_THROW(renderer_.render(r, image_, stats_), std::invalid_argument) << w << "x" << h;
  }
  r.camera = make_camera_view({0, 1.5f, 4}, {0, 1, 0}, {0, 1, 0}, 1.0f, 1920, 1080);
  r.instances.clear();
  renderer_.render(r, image_, stats_);
  EXPECT_EQ(image_.size(), std::size_t{1920 * 1080 * 4});
}

TEST_F(CrowdRendererTest, BadInstancesAndModelsAreRejected) {
  const crowd::SkinnedModel bar = test::bar_model(kGreen);
  const int id = add(bar, 1);
  FrameRequest r = request_at({1, 0.5f, 3.5f}, {1, 0.5f, 0});
  r.instances = {placed(id, {0, 0, 0}, 2)};  // the bar has frames 0 and 1
  EXPECT_THROW(renderer_.render(r, image_, stats_), std::invalid_argument);
  r.instances = {placed(id + 1, {0, 0, 0})};
  EXPECT_THROW(renderer_.render(r, image_, stats_), std::invalid_argument);
  r.instances = {placed(id, {0, 0, 0})};
  r.instances[0].animation = 1;
  EXPECT_THROW(renderer_.render(r, image_, stats_), std::invalid_argument);

  crowd::ClusterHierarchy h = test::test_hierarchy(bar, 1);
  h.indices[5] = static_cast<std::uint32_t>(bar.positions.size());
  EXPECT_THROW(renderer_.add_model(bar, h), std::invalid_argument);
  h = test::test_hierarchy(bar, 1);
  h.clusters[static_cast<std::size_t>(h.root)].children[1] = h.clusters[static_cast<std::size_t>(h.root)].children[0];
  EXPECT_THROW(renderer_.add_model(bar, h), std::invalid_argument);
  crowd::SkinnedModel bad_joint = bar;
  bad_joint.joints[3][0] = 7;
  EXPECT_THROW(renderer_.add_model(bad_joint, test::test_hierarchy(bar, 1)), std::invalid_argument);
  crowd::SkinnedModel short_pose = bar;
  short_pose.animations[0].poses[1].skinning.pop_back();
  EXPECT_THROW(renderer_.add_model(short_pose, test::test_hierarchy(bar, 1)), std::invalid_argument);
  EXPECT_EQ(renderer_.model_count(), 1);
}

}  // namespace
}  // namespace tourmap::render
