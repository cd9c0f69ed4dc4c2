#include "crowd_view.hpp"

#include "crowd/scene.hpp"

#include <cmath>
#include <functional>

namespace tourmap::api {
namespace {

[[noreturn]] void bad(const std::string& field, const std::string& message) {
  throw ApiError(400, "bad_request", message, field);
}

double number(const nlohmann::json& msg, const char* field, double lo, double hi) {
  const auto& v = msg.at(field);
  if (!v.is_number()) bad(field, std::string(field) + " must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi)
    bad(field, std::string(field) + " must be between " + nlohmann::json(lo).dump() + " and " + nlohmann::json(hi).dump());
  return x;
}

bool boolean(const nlohmann::json& msg, const char* field) {
  const auto& v = msg.at(field);
  if (!v.is_boolean()) bad(field, std::string(field) + " must be true or false");
  return v.get<bool>();
}

std::array<float, 3> point(const nlohmann::json& v, const std::string& field, float max_abs) {
  if (!v.is_array() || v.size() != 3) bad(field, field + " must be [x, y, z]");
  std::array<float, 3> p{};
  for (std::size_t i = 0; i < 3; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()) || std::abs(v[i].get<double>()) > max_abs)
      bad(field, field + " must hold three finite numbers within +-" + std::to_string(static_cast<int>(max_abs)) + " m");
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
  if (!msg.is_object()) bad("type", "a message must be a JSON object");
  if (!msg.contains("type") || msg["type"] != "view") bad("type", "type must be \"view\"");
  CrowdView v = current;
  if (msg.contains("scene")) {
    if (!msg["scene"].is_string()) bad("scene", "scene must be a string");
    const std::string id = msg["scene"].get<std::string>();
    const auto* spec = crowd::find_scene_spec(id);
    if (!spec) bad("scene", "unknown scene '" + id.substr(0, 64) + "'");
    if (id != v.scene) {  // a new scene: its own defaults
      v.has_camera = false;
      v.count = 0;
    }
    v.scene = id;
  }
  if (v.scene.empty()) bad("scene", "the first view message must name a scene");
  const auto* spec = crowd::find_scene_spec(v.scene);
  if (msg.contains("mode")) {
    const auto& m = msg["mode"];
    if (m == "nolod") v.mode = CrowdMode::no_lod;
    else if (m == "vdr") v.mode = CrowdMode::vdr;
    else if (m == "vdr+oc") v.mode = CrowdMode::vdr_oc;
    else bad("mode", "mode must be one of nolod, vdr, vdr+oc");
  }
  if (msg.contains("poe")) v.poe = static_cast<float>(number(msg, "poe", limits.min_poe, limits.max_poe));
  if (msg.contains("width")) v.width = static_cast<int>(number(msg, "width", limits.min_width, limits.max_width));
  if (msg.contains("height")) v.height = static_cast<int>(number(msg, "height", limits.min_height, limits.max_height));
  if (msg.contains("quality"))
    v.quality = static_cast<int>(number(msg, "quality", limits.min_quality, limits.max_quality));
  if (msg.contains("heatmap")) v.heatmap = boolean(msg, "heatmap");
  if (msg.contains("animate")) v.animate = boolean(msg, "animate");
  if (msg.contains("count"))
    v.count = static_cast<int>(number(msg, "count", spec->min_count, spec->max_count));
  if (msg.contains("camera")) {
    const auto& c = msg["camera"];
    if (!c.is_object()) bad("camera", "camera must be an object {eye, target, fov}");
    if (!c.contains("eye") || !c.contains("target")) bad("camera", "camera needs eye and target");
    v.eye = point(c["eye"], "camera.eye", limits.max_coordinate);
    v.target = point(c["target"], "camera.target", limits.max_coordinate);
    const float dx = v.eye[0] - v.target[0], dy = v.eye[1] - v.target[1], dz = v.eye[2] - v.target[2];
    if (dx * dx + dy * dy + dz * dz < 1e-6f) bad("camera.target", "camera.eye and camera.target must differ");
    if (c.contains("fov")) {
      if (!c["fov"].is_number() || !std::isfinite(c["fov"].get<double>()) || c["fov"].get<double>() < limits.min_fov ||
          c["fov"].get<double>() > limits.max_fov)
        bad("camera.fov", "camera.fov must be between " + std::to_string(static_cast<int>(limits.min_fov)) + " and " +
                              std::to_string(static_cast<int>(limits.max_fov)) + " degrees");
      v.fov = c["fov"].get<float>();
    }
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
                      {"bounds",
                       {{"min", {s.bounds.min().x(), s.bounds.min().y(), s.bounds.min().z()}},
                        {"max", {s.bounds.max().x(), s.bounds.max().y(), s.bounds.max().z()}}}},
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
