#include "crowd_view.hpp"

#include "params.hpp"

#include "crowd/scene.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace tourmap::api {
namespace {

std::array<float, 3> point(const nlohmann::json& v, const std::string& field, float max_abs) {
  if (!v.is_array() || v.size() != 3) throw bad(field, "expected [x, y, z]");
  std::array<float, 3> p{};
  for (std::size_t i = 0; i < 3; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()) || std::abs(v[i].get<double>()) > max_abs)
      throw bad(field, "expected three finite numbers within +-" + std::to_string(static_cast<int>(max_abs)) + " m");
    p[i] = v[i].get<float>();
  }
  return p;
}

}  // namespace

const char* mode_name(CrowdMode m) {
  switch (m) {
    case CrowdMode::no_lod: return "nolod";
    case CrowdMode::vdr: return "vdr";
    case CrowdMode::vdr_oc: return "vdr+oc";
  }
  return "?";
}

CrowdView apply_view_message(const nlohmann::json& msg, const CrowdView& current, const CrowdLimits& limits) {
  if (!msg.is_object()) throw bad("type", "a message must be a JSON object");
  if (!msg.contains("type") || msg["type"] != "view") throw bad("type", "expected \"view\" (or \"ack\")");
  CrowdView v = current;
  if (msg.contains("scene")) {
    if (!msg["scene"].is_string()) throw bad("scene", "expected a string");
    const std::string& id = msg["scene"].get_ref<const std::string&>();
    const auto* spec = crowd::find_scene_spec(id);
    if (!spec) throw bad("scene", "unknown scene '" + shown(id) + "'");
    if (id != v.scene) {  // a new scene: its own defaults
      v.has_camera = false;
      v.count = 0;
    }
    v.scene = id;
  }
  if (v.scene.empty()) throw bad("scene", "the first view message must name a scene");
  const auto* spec = crowd::find_scene_spec(v.scene);
  if (const auto* m = member(msg, "mode")) {
    const auto name = json_choice(*m, "mode", {"nolod", "vdr", "vdr+oc"});
    v.mode = name == "nolod" ? CrowdMode::no_lod : name == "vdr" ? CrowdMode::vdr : CrowdMode::vdr_oc;
  }
  if (const auto* x = member(msg, "poe")) v.poe = static_cast<float>(json_number(*x, "poe", limits.min_poe, limits.max_poe));
  if (const auto* x = member(msg, "width"))
    v.width = static_cast<int>(json_number(*x, "width", limits.min_width, limits.max_width));
  if (const auto* x = member(msg, "height"))
    v.height = static_cast<int>(json_number(*x, "height", limits.min_height, limits.max_height));
  if (const auto* x = member(msg, "quality"))
    v.quality = static_cast<int>(json_number(*x, "quality", limits.min_quality, limits.max_quality));
  if (const auto* x = member(msg, "target_fps"))
    v.target_fps = static_cast<int>(json_number(*x, "target_fps", 0, limits.max_fps));
  if (const auto* x = member(msg, "interacting")) v.interacting = json_bool(*x, "interacting") ? 1 : 0;
  if (const auto* x = member(msg, "heatmap")) v.heatmap = json_bool(*x, "heatmap");
  if (const auto* x = member(msg, "animate")) v.animate = json_bool(*x, "animate");
  if (const auto* x = member(msg, "count"))
    v.count = static_cast<int>(json_number(*x, "count", spec->min_count, spec->max_count));
  if (const auto* c = member(msg, "camera")) {
    if (!c->is_object()) throw bad("camera", "expected an object {eye, target, fov}");
    if (!c->contains("eye") || !c->contains("target")) throw bad("camera", "needs eye and target");
    v.eye = point((*c)["eye"], "camera.eye", limits.max_coordinate);
    v.target = point((*c)["target"], "camera.target", limits.max_coordinate);
    const float dx = v.eye[0] - v.target[0], dy = v.eye[1] - v.target[1], dz = v.eye[2] - v.target[2];
    if (dx * dx + dy * dy + dz * dz < 1e-6f) throw bad("camera.target", "camera.eye and camera.target must differ");
    if (const auto* fov = member(*c, "fov")) v.fov = static_cast<float>(json_number(*fov, "camera.fov", limits.min_fov, limits.max_fov));
    v.has_camera = true;
  }
  return v;
}

nlohmann::json model_attribution_json() {
  return nlohmann::json::array({
      {{"model", "CesiumMan"}, {"text", "\"Cesium Man\" © 2017 Cesium, CC-BY 4.0"},
       {"url", "https://creativecommons.org/licenses/by/4.0/"}},
      {{"model", "Mannequiny"}, {"text", "Mannequiny © 2020 GDQuest and contributors, CC-BY 4.0"},
       {"url", "https://www.gdquest.com/"}},
      {{"model", "RobotExpressive"}, {"text", "RobotExpressive by Tomás Laulhé, modifications by Don McCurdy, CC0 1.0"},
       {"url", "https://creativecommons.org/publicdomain/zero/1.0/"}},
      {{"model", "Fox"},
       {"text", "Fox: model by PixelMannen (CC0 1.0); rigging and animation © 2014 tomkranis, CC-BY 4.0; "
                "glTF conversion © 2017 @AsoboStudio and @scurest, CC-BY 4.0"},
       {"url", "https://creativecommons.org/licenses/by/4.0/"}},
      {{"model", "Horse, Donkey, Cow"}, {"text", "Ultimate Animated Animals by Quaternius, CC0 1.0"},
       {"url", "https://quaternius.com"}},
  });
}

namespace {

// The scenes answer lists at most this many occluder boxes per scene (the scenes have 12 to 60):
// a bound on the answer, whatever a future scene holds. `occluders` stays the full count.
constexpr std::size_t kMaxOccluderBoxes = 256;

nlohmann::json box_json(const crowd::Box3& b) {
  return {{"min", {b.min().x(), b.min().y(), b.min().z()}}, {"max", {b.max().x(), b.max().y(), b.max().z()}}};
}

nlohmann::json occluder_boxes_json(const std::vector<crowd::Box3>& occluders) {
  nlohmann::json boxes = nlohmann::json::array();
  const std::size_t n = std::min(occluders.size(), kMaxOccluderBoxes);
  for (std::size_t i = 0; i < n; ++i) boxes.push_back(box_json(occluders[i]));
  return boxes;
}

}  // namespace

nlohmann::json crowd_scenes_json(const CrowdLimits& limits,
                                 const std::function<long long(const std::string&, int)>& triangles_of) {
  nlohmann::json scenes = nlohmann::json::array();
  for (const auto& spec : crowd::scene_specs()) {
    const crowd::SceneState s = crowd::build_scene(spec, spec.default_count);
    nlohmann::json models = nlohmann::json::array();
    for (const auto& c : spec.characters) models.push_back(c.name);
    const auto& cam = s.default_camera;
    const long long tris = triangles_of ? triangles_of(spec.id, spec.default_count) : -1;
    scenes.push_back({{"id", spec.id},
                      {"title", spec.title},
                      {"description", spec.description},
                      {"characters", s.count},
                      {"models", models},
                      {"triangles", tris >= 0 ? nlohmann::json(tris) : nlohmann::json(nullptr)},
                      {"occluders", s.occluders.size()},
                      {"occluder_boxes", occluder_boxes_json(s.occluders)},
                      {"bounds", box_json(s.bounds)},
                      {"default_camera",
                       {{"eye", {cam.eye.x(), cam.eye.y(), cam.eye.z()}},
                        {"target", {cam.target.x(), cam.target.y(), cam.target.z()}},
                        {"fov", cam.fov_deg}}},
                      {"count", {{"default", spec.default_count}, {"min", spec.min_count}, {"max", spec.max_count}}}});
  }
  return {{"scenes", scenes},
          {"modes", {"nolod", "vdr", "vdr+oc"}},
          {"limits",
           {{"min_width", limits.min_width}, {"min_height", limits.min_height}, {"max_width", limits.max_width},
            {"max_height", limits.max_height}, {"max_streams", limits.max_streams},
            {"max_messages_per_s", limits.max_messages_per_s}, {"max_fps", limits.max_fps},
            {"poe", {{"min", limits.min_poe}, {"max", limits.max_poe}}},
            {"quality", {{"min", limits.min_quality}, {"max", limits.max_quality}}},
            {"fov", {{"min", limits.min_fov}, {"max", limits.max_fov}}}}},
          {"attribution", model_attribution_json()}};
}

}  // namespace tourmap::api
