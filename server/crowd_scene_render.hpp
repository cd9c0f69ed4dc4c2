#pragma once
// A crowd scene made ready for the renderer (characters loaded and uploaded, occluders as one
// static model) and the frame request for a moment and a camera. Shared by the stream and the
// benchmark, so both measure the same code path.

#include "api/crowd_assets.hpp"
#include "crowd/scene.hpp"
#include "render/crowd_renderer.hpp"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace tourmap::server {

struct PreparedScene {
  crowd::SceneState scene;
  std::vector<std::shared_ptr<const api::CrowdCharacter>> characters;
  std::vector<int> model_ids;  // renderer model per character
  int boxes_model = -1;
  long long full_triangles = 0;
};

// Loads/builds the characters (progress reported), uploads what the renderer does not have yet
// (`uploaded` maps character keys to renderer model ids and is updated).
std::unique_ptr<PreparedScene> prepare_scene(api::CrowdAssets& assets, render::CrowdRenderer& renderer,
                                             std::map<std::string, int>& uploaded, const crowd::SceneSpec& spec,
                                             int count, const api::CrowdProgress& progress);

struct SceneCamera {
  crowd::Vec3 eye, target;
  float fov_deg = 60;
  int width = 1280, height = 720;
};

// The instances at time t (s): the static occluders first, then every character posed at the
// frame of its animation clock.
void scene_frame_request(const PreparedScene& p, double t, const SceneCamera& camera, render::RenderMode mode,
                         float poe, bool heatmap, render::FrameRequest& out, std::vector<crowd::Placement>& scratch);

}  // namespace tourmap::server
