#pragma once
// The crowd benchmark scenes of sec. 3.6 with deterministic motion: where every character is at
// time t, and the static occluders (walls, booths, rocks) as boxes. No models are loaded here:
// a scene names its character models (files under the data directory's models/) and the
// service loads them.

#include "skinned_model.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace tourmap::crowd {

struct SceneCharacter {
  std::string name;       // e.g. "CesiumMan"
  std::string file;       // relative to the models directory, e.g. "humans/CesiumMan.glb"
  std::string animation;  // preferred animation (case-insensitive substring); "" = the first
  int subdivision = 0;    // Loop levels, to reach the paper's per-character triangle counts
  float height_m = 1.75f; // characters are scaled to this height
};

enum class SceneLayout {
  blocks,     // agents walk loops in the corridors around a grid of blocks (rooms, booths)
  open_field  // a herd runs across a plain, wrapping around; a few rocks
};

struct SceneSpec {
  std::string id, title, description;
  std::vector<SceneCharacter> characters;
  int default_count = 200, min_count = 1, max_count = 2000;
  SceneLayout layout = SceneLayout::blocks;
  // blocks: a rows x cols grid of blocks `block_m` wide, corridors `corridor_m` wide
  int rows = 3, cols = 4;
  float block_m = 8, corridor_m = 4, wall_height_m = 3;
  bool hollow_blocks = true;  // rooms (four walls with a door) rather than solid booths
  float speed_mps = 1.3f;
};

// The three scenes: office (200 humans, walls), exhibition (1K humans, booths), stampede (5K animals).
const std::vector<SceneSpec>& scene_specs();
const SceneSpec* find_scene_spec(std::string_view id);

struct Camera {
  Vec3 eye, target;
  float fov_deg = 60;
};

// One character's motion: a closed polyline walked at constant speed, or a straight run that
// wraps around the field.
struct Agent {
  int character = 0;           // index into SceneSpec::characters
  std::vector<Vec3> loop;      // closed path (blocks), or {start, direction} (open_field)
  float length_m = 0;          // loop length (blocks) or field length (open_field)
  float speed_mps = 1.3f;
  float offset_m = 0;          // where on the path it is at t = 0
  float phase_s = 0;           // animation phase
};

struct SceneState {
  const SceneSpec* spec = nullptr;
  int count = 0;
  std::vector<Agent> agents;
  std::vector<Box3> occluders;  // static boxes (walls, booths, rocks)
  Box3 ground;                  // a thin box under everything
  Box3 bounds;
  Camera default_camera;
};

// Deterministic: the same spec and count give the same scene. count is clamped to the spec's range.
SceneState build_scene(const SceneSpec& spec, int count);

struct Placement {
  int character = 0;
  Vec3 position;      // feet on the ground (y = 0)
  float heading = 0;  // radians about +Y; 0 faces +Z (glTF forward)
  float anim_time_s = 0;
};

// Where every agent is at time t (seconds).
void place_agents(const SceneState& scene, double t, std::vector<Placement>& out);

// Scene space <- character space for a placement: a character's feet at its origin, facing +Z.
Affine placement_transform(const Placement& p);

// A static model of boxes (occluders and ground), one identity joint and one pose, with
// per-box colours (ground first, then the occluders).
SkinnedModel boxes_model(const SceneState& scene);

}  // namespace tourmap::crowd
