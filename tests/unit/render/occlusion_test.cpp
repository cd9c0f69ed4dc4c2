#include "render/occlusion.hpp"

#include "render/camera.hpp"
#include "render_test_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace tourmap::render {
namespace {

struct Tree {
  crowd::ClusterHierarchy h = test::test_hierarchy(test::box_model({1, 1, 1}, {200, 0, 0, 255}, 2), 2);
  int root = h.root;
  int a = h.clusters[static_cast<std::size_t>(root)].children[0];
  int b = h.clusters[static_cast<std::size_t>(root)].children[1];
  int a0 = h.clusters[static_cast<std::size_t>(a)].children[0];
  int a1 = h.clusters[static_cast<std::size_t>(a)].children[1];
  int b0 = h.clusters[static_cast<std::size_t>(b)].children[0];
  int b1 = h.clusters[static_cast<std::size_t>(b)].children[1];
};

struct Split {
  std::vector<int> in_pvs, occludees;
};

Split split(const Tree& t, std::vector<int> visible_last, std::vector<int> cut, std::vector<std::uint8_t>& marks) {
  Split s;
  split_by_pvs(t.h, visible_last, cut, s.in_pvs, s.occludees, marks);
  return s;
}

TEST(SplitByPvs, ClusterAncestorOrDescendantVisibleLastFrameIsInThePvs) {
  const Tree t;
  std::vector<std::uint8_t> marks;
  // Coarsened: a was refined into a0 (visible) last frame.
  Split s = split(t, {t.a0}, {t.a, t.b}, marks);
  EXPECT_EQ(s.in_pvs, std::vector<int>{t.a});
  EXPECT_EQ(s.occludees, std::vector<int>{t.b});
  // Refined: a was visible, now its leaves are in the cut.
  s = split(t, {t.a}, {t.a0, t.a1, t.b0, t.b1}, marks);
  EXPECT_EQ(s.in_pvs, (std::vector<int>{t.a0, t.a1}));
  EXPECT_EQ(s.occludees, (std::vector<int>{t.b0, t.b1}));
  // Same cut: a sibling of a visible cluster is not related to it.
  s = split(t, {t.a0}, {t.a0, t.a1, t.b}, marks);
  EXPECT_EQ(s.in_pvs, std::vector<int>{t.a0});
  EXPECT_EQ(s.occludees, (std::vector<int>{t.a1, t.b}));
  // The root seen last frame makes everything potentially visible.
  s = split(t, {t.root}, {t.a0, t.a1, t.b0, t.b1}, marks);
  EXPECT_EQ(s.in_pvs.size(), 4u);
  // Nothing seen: everything is tested; ids outside the hierarchy are ignored.
  s = split(t, {-3, 99}, {t.a, t.b}, marks);
  EXPECT_TRUE(s.in_pvs.empty());
  EXPECT_EQ(s.occludees.size(), 2u);
  EXPECT_TRUE(std::all_of(marks.begin(), marks.end(), [](std::uint8_t m) { return m == 0; }));
}

TEST(FrameCoherence, ResetsEveryNFramesOnJumpsAndOnNewInstanceLists) {
  CoherenceOptions options;
  options.reset_every_frames = 3;
  options.jump_distance_m = 1.0f;
  FrameCoherence c(options);
  crowd::CameraView view = make_camera_view({0, 1, 5}, {0, 1, 0}, {0, 1, 0}, 1.0f, 160, 120);
  const std::vector<int> models{0, 0};
  EXPECT_TRUE(c.begin_frame(view, models));
  c.current(1) = {4, 5};
  c.end_frame();
  EXPECT_FALSE(c.begin_frame(view, models));
  EXPECT_EQ(c.previous(1), (std::vector<int>{4, 5}));
  EXPECT_TRUE(c.current(1).empty());
  c.current(1) = {6};
  c.end_frame();
  EXPECT_FALSE(c.begin_frame(view, models));
  EXPECT_EQ(c.previous(1), std::vector<int>{6});
  c.end_frame();
  EXPECT_TRUE(c.begin_frame(view, models));  // the 4th frame: n = 3 reached
  EXPECT_TRUE(c.previous(1).empty());
  c.end_frame();

  view = make_camera_view({0.3f, 1, 5}, {0.3f, 1, 0}, {0, 1, 0}, 1.0f, 160, 120);  // small step
  EXPECT_FALSE(c.begin_frame(view, models));
  c.end_frame();
  view = make_camera_view({0.3f, 1, 5}, {5, 1, 0}, {0, 1, 0}, 1.0f, 160, 120);  // turned ~45 degrees
  EXPECT_TRUE(c.begin_frame(view, models));
  c.end_frame();
  view = make_camera_view({2.5f, 1, 5}, {7.2f, 1, 0}, {0, 1, 0}, 1.0f, 160, 120);  // moved 2.2 m
  EXPECT_TRUE(c.begin_frame(view, models));
  c.end_frame();
  EXPECT_TRUE(c.begin_frame(view, std::vector<int>{0, 1}));  // instance 1 changed model
  c.end_frame();
  c.reset();
  EXPECT_TRUE(c.begin_frame(view, std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace tourmap::render
