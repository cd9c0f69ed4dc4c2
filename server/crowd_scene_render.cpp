#include "crowd_scene_render.hpp"

#include "render/camera.hpp"

#include <cmath>

namespace tourmap::server {

std::unique_ptr<PreparedScene> prepare_scene(api::CrowdAssets& assets, render::CrowdRenderer& renderer,
                                             std::map<std::string, int>& uploaded, const crowd::SceneSpec& spec,
                                             int count, const api::CrowdProgress& progress) {
  auto p = std::make_unique<PreparedScene>();
  p->scene = crowd::build_scene(spec, count);
  p->characters = assets.characters(spec, progress);
  const int total = static_cast<int>(spec.characters.size());
  if (progress) progress("uploading", "", total, total);
  for (std::size_t i = 0; i < spec.characters.size(); ++i) {
    const std::string key = api::crowd_character_key(spec.characters[i]);
    auto it = uploaded.find(key);
    if (it == uploaded.end())
      it = uploaded.emplace(key, renderer.add_model(p->characters[i]->model, p->characters[i]->hierarchy)).first;
    p->model_ids.push_back(it->second);
  }
  // The occluders and the ground: one static model whose hierarchy is a single cluster.
  const crowd::SkinnedModel boxes = crowd::boxes_model(p->scene);
  crowd::ClusterHierarchy flat;
  crowd::Cluster root;
  root.index_count = static_cast<std::uint32_t>(boxes.indices.size());
  root.bounds = p->scene.bounds;
  flat.clusters.push_back(root);
  flat.root = 0;
  flat.indices = boxes.indices;
  p->boxes_model = renderer.add_model(boxes, flat);
  p->full_triangles = assets.full_triangles(spec, count);
  return p;
}

void scene_frame_request(const PreparedScene& p, double t, const SceneCamera& camera, render::RenderMode mode,
                         float poe, bool heatmap, render::FrameRequest& out, std::vector<crowd::Placement>& scratch) {
  // +Y up, except when looking (nearly) straight up or down: a top view is a view users orbit to.
  const crowd::Vec3 forward = (camera.target - camera.eye).normalized();
  const crowd::Vec3 up = std::abs(forward.y()) > 0.999f ? crowd::Vec3::UnitZ() : crowd::Vec3::UnitY();
  out.camera = render::make_camera_view(camera.eye, camera.target, up,
                                        camera.fov_deg * 3.14159265f / 180.f, camera.width, camera.height, 0.1f, 2000.f);
  out.mode = mode;
  out.poe = poe;
  out.heatmap = heatmap;
  out.ground = true;  // an endless ground plane under the scene's own floor box
  crowd::place_agents(p.scene, t, scratch);
  out.instances.clear();
  out.instances.reserve(scratch.size() + 1);
  out.instances.push_back({p.boxes_model, crowd::Affine::Identity(), 0, 0});
  for (const auto& pl : scratch) {
    const auto& ch = *p.characters[static_cast<std::size_t>(pl.character)];
    const auto& anim = ch.model.animations[0];
    const int frames = std::max(1, static_cast<int>(anim.poses.size()));
    const int frame = static_cast<int>(std::floor(pl.anim_time_s * anim.fps)) % frames;
    out.instances.push_back(
        {p.model_ids[static_cast<std::size_t>(pl.character)], crowd::placement_transform(pl) * ch.normalize, 0, frame});
  }
}

}  // namespace tourmap::server
