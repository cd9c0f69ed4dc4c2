#include "api/crowd_view.hpp"

#include <gtest/gtest.h>

namespace tourmap::api {
namespace {

using nlohmann::json;

std::string field_of(const json& msg, const CrowdView& current = {}) {
  try {
    apply_view_message(msg, current, CrowdLimits{});
  } catch (const ApiError& e) {
    EXPECT_EQ(e.status, 400);
    return e.field;
  }
  return "<accepted>";
}

TEST(CrowdViewMessage, FirstMessageNeedsAKnownScene) {
  EXPECT_EQ(field_of(json{{"type", "view"}}), "scene");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"scene", "moon"}}), "scene");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"scene", 3}}), "scene");
  EXPECT_EQ(field_of(json{{"type", "look"}, {"scene", "office"}}), "type");
  EXPECT_EQ(field_of(json::array()), "type");
  const CrowdView v = apply_view_message(json{{"type", "view"}, {"scene", "office"}}, {}, {});
  EXPECT_EQ(v.scene, "office");
  EXPECT_EQ(v.mode, CrowdMode::vdr_oc);
  EXPECT_FLOAT_EQ(v.poe, 0.5f);
  EXPECT_FALSE(v.has_camera);
}

TEST(CrowdViewMessage, LaterMessagesChangeOnlyWhatTheyContain) {
  CrowdView v = apply_view_message(json{{"type", "view"}, {"scene", "office"}, {"poe", 2}, {"width", 320}, {"height", 200}}, {}, {});
  v = apply_view_message(json{{"type", "view"}, {"mode", "nolod"}}, v, {});
  EXPECT_EQ(v.scene, "office");
  EXPECT_EQ(v.mode, CrowdMode::no_lod);
  EXPECT_FLOAT_EQ(v.poe, 2.f);
  EXPECT_EQ(v.width, 320);
  v = apply_view_message(json::parse(R"({"type":"view","camera":{"eye":[1,2,3],"target":[0,0,0],"fov":45}})"), v, {});
  EXPECT_TRUE(v.has_camera);
  EXPECT_FLOAT_EQ(v.eye[2], 3.f);
  EXPECT_FLOAT_EQ(v.fov, 45.f);
  // A new scene drops the old camera and count.
  v = apply_view_message(json{{"type", "view"}, {"scene", "stampede"}}, v, {});
  EXPECT_FALSE(v.has_camera);
  EXPECT_EQ(v.count, 0);
}

TEST(CrowdViewMessage, BadFieldsAreNamed) {
  CrowdView office;
  office.scene = "office";
  EXPECT_EQ(field_of(json{{"type", "view"}, {"poe", 0}}, office), "poe");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"poe", -1}}, office), "poe");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"poe", "big"}}, office), "poe");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"poe", 1e9}}, office), "poe");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"width", 100000}}, office), "width");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"height", 10}}, office), "height");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"quality", 101}}, office), "quality");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"mode", "fast"}}, office), "mode");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"heatmap", "yes"}}, office), "heatmap");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"count", 0}}, office), "count");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"count", 1000000}}, office), "count");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"camera", 5}}, office), "camera");
  EXPECT_EQ(field_of(json::parse(R"({"type":"view","camera":{"eye":[1,2],"target":[0,0,0]}})"), office), "camera.eye");
  EXPECT_EQ(field_of(json::parse(R"({"type":"view","camera":{"eye":[1,2,3],"target":[0,"a",0]}})"), office),
            "camera.target");
  EXPECT_EQ(field_of(json::parse(R"({"type":"view","camera":{"eye":[1,2,3],"target":[1,2,3]}})"), office),
            "camera.target");
  EXPECT_EQ(field_of(json::parse(R"({"type":"view","camera":{"eye":[1e9,2,3],"target":[0,0,0]}})"), office),
            "camera.eye");
  EXPECT_EQ(field_of(json::parse(R"({"type":"view","camera":{"eye":[1,2,3],"target":[0,0,0],"fov":179}})"), office),
            "camera.fov");
  EXPECT_EQ(field_of(json{{"type", "view"}, {"poe", 4}}, office), "<accepted>");
}

TEST(CrowdScenesJson, ListsTheScenesLimitsAndAttribution) {
  const json j = crowd_scenes_json(CrowdLimits{}, [](const std::string& id, int) { return id == "office" ? 42 : -1; });
  ASSERT_EQ(j["scenes"].size(), 3u);
  EXPECT_EQ(j["scenes"][0]["id"], "office");
  EXPECT_EQ(j["scenes"][0]["triangles"], 42);
  EXPECT_TRUE(j["scenes"][1]["triangles"].is_null());
  EXPECT_EQ(j["scenes"][2]["characters"], 5000);
  EXPECT_EQ(j["limits"]["max_width"], 1920);
  EXPECT_GE(j["attribution"].size(), 5u);
  EXPECT_EQ(j["scenes"][0]["default_camera"]["eye"].size(), 3u);
}

}  // namespace
}  // namespace tourmap::api
