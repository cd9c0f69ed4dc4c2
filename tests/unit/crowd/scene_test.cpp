#include "crowd/scene.hpp"

#include <gtest/gtest.h>

namespace tourmap::crowd {
namespace {

TEST(CrowdScene, TheThreePaperScenesExistWithTheirDefaultCounts) {
  ASSERT_NE(find_scene_spec("office"), nullptr);
  ASSERT_NE(find_scene_spec("exhibition"), nullptr);
  ASSERT_NE(find_scene_spec("stampede"), nullptr);
  EXPECT_EQ(find_scene_spec("nope"), nullptr);
  EXPECT_EQ(find_scene_spec("office")->default_count, 200);
  EXPECT_EQ(find_scene_spec("exhibition")->default_count, 1000);
  EXPECT_EQ(find_scene_spec("stampede")->default_count, 5000);
}

TEST(CrowdScene, BuildingIsDeterministicAndClampsTheCount) {
  const auto& spec = *find_scene_spec("office");
  const SceneState a = build_scene(spec, 50), b = build_scene(spec, 50);
  ASSERT_EQ(a.agents.size(), 50u);
  std::vector<Placement> pa, pb;
  place_agents(a, 12.5, pa);
  place_agents(b, 12.5, pb);
  ASSERT_EQ(pa.size(), pb.size());
  for (std::size_t i = 0; i < pa.size(); ++i) EXPECT_TRUE(pa[i].position.isApprox(pb[i].position));
  EXPECT_EQ(build_scene(spec, 0).count, spec.min_count);
  EXPECT_EQ(build_scene(spec, 1000000).count, spec.max_count);
}

TEST(CrowdScene, WalkersStayInTheCorridorsAndMove) {
  for (const char* id : {"office", "exhibition"}) {
    const auto& spec = *find_scene_spec(id);
    const SceneState s = build_scene(spec, 300);
    std::vector<Placement> now, later;
    for (double t : {0.0, 3.3, 17.0, 101.0}) {
      place_agents(s, t, now);
      place_agents(s, t + 0.5, later);
      for (std::size_t i = 0; i < now.size(); ++i) {
        for (const auto& wall : s.occluders) {
          const Vec3 p = now[i].position + Vec3(0, 1, 0);  // at chest height
          EXPECT_FALSE(wall.contains(p)) << id << " agent " << i << " inside a wall at t=" << t;
        }
        EXPECT_TRUE(s.ground.min().x() <= now[i].position.x() && now[i].position.x() <= s.ground.max().x());
        const float moved = (later[i].position - now[i].position).norm();
        EXPECT_GT(moved, 0.2f);   // about 1.3 m/s for 0.5 s
        EXPECT_LT(moved, 1.0f);
      }
    }
  }
}

TEST(CrowdScene, StampedeRunsAlongXAndWraps) {
  const SceneState s = build_scene(*find_scene_spec("stampede"), 100);
  std::vector<Placement> p;
  place_agents(s, 1000.0, p);
  for (const auto& q : p) {
    EXPECT_GE(q.position.x(), 0.f);
    EXPECT_LE(q.position.x(), s.ground.max().x() + 1e-3f);
    EXPECT_NEAR(q.heading, 1.5707963f, 1e-4f);  // facing +X
  }
}

TEST(CrowdScene, BoxesModelHasTwelveTrianglesPerBoxAndIsStatic) {
  const SceneState s = build_scene(*find_scene_spec("office"), 10);
  const SkinnedModel m = boxes_model(s);
  EXPECT_EQ(m.triangle_count(), 12 * (s.occluders.size() + 1));
  EXPECT_TRUE(m.is_static());
  // Outward normals: each triangle's winding agrees with its vertex normal.
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const Vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]], c = m.positions[m.indices[3 * t + 2]];
    EXPECT_GT((b - a).cross(c - a).dot(m.normals[m.indices[3 * t]]), 0.f);
  }
}

}  // namespace
}  // namespace tourmap::crowd
