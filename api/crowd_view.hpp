#pragma once
// The crowd stream's contract without the transport: the limits, the scene catalogue JSON
// (GET /api/v1/crowd/scenes) and the validation of the client's "view" messages
// (WS /api/v1/crowd/stream). Bad fields throw ApiError naming the field.

#include "http.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <functional>
#include <string>

namespace tourmap::api {

struct CrowdLimits {
  int min_width = 64, min_height = 64, max_width = 1920, max_height = 1080;
  float min_poe = 0.05f, max_poe = 64.f;
  int min_quality = 10, max_quality = 95;
  float min_fov = 10, max_fov = 120;
  float max_coordinate = 100000;  // metres, camera eye/target
  unsigned max_streams = 4;
  int max_messages_per_s = 60;    // more closes the stream (policy violation)
  int max_fps = 30;
};

enum class CrowdMode { no_lod, vdr, vdr_oc };
const char* mode_name(CrowdMode m);

struct CrowdView {
  std::string scene;
  CrowdMode mode = CrowdMode::vdr_oc;
  float poe = 0.5f;
  int width = 1280, height = 720, quality = 75;
  std::array<float, 3> eye{0, 0, 0}, target{0, 0, 0};
  float fov = 60;
  bool has_camera = false;  // false: use the scene's default camera
  bool heatmap = false, animate = true;
  int count = 0;            // 0: the scene's default
  // Frames per second to hold while the camera moves or the crowd animates, by lowering the
  // resolution, LOD and JPEG quality; a still camera then gets one full-quality frame.
  // 0: every frame at full quality.
  int target_fps = 15;
  // The client says whether the user is moving the camera (a drag or a key held: 1) or has let
  // go (0), as vtk.js's start/end interaction do: no full-quality frame mid-drag, and the one at
  // the end at once. -1: never said; the server then guesses from camera moves (kCameraSettle).
  int interacting = -1;

  bool operator==(const CrowdView&) const = default;
  // Same eye, target and field of view (or both the scene's default camera).
  bool same_camera(const CrowdView& o) const {
    return has_camera == o.has_camera && (!has_camera || (eye == o.eye && target == o.target && fov == o.fov));
  }
};

// Applies a {"type":"view", ...} message on top of `current` (fields left out keep their value).
// The first message must name a scene. Throws ApiError(400, ..., field).
CrowdView apply_view_message(const nlohmann::json& msg, const CrowdView& current, const CrowdLimits& limits);

// The catalogue: scenes (with full-resolution triangle counts when known), modes, limits,
// model attributions. `triangles_of(scene id, count)` may return -1 when not known yet.
nlohmann::json crowd_scenes_json(const CrowdLimits& limits, const std::function<long long(const std::string&, int)>& triangles_of);

// Attribution lines for the models a scene uses (from the data's PROVENANCE.md).
nlohmann::json model_attribution_json();

}  // namespace tourmap::api
