#pragma once
// Headless crowd rendering (sec. 3.5): per instance a LOD cut with view-frustum culling
// (sec. 3.5.1), GPU skinning (eq. 3.1), instanced multi-draw of the cut, and optionally
// conservative occlusion culling with frame-to-frame coherence (sec. 3.5.2). One renderer per
// EglContext, used on the context's thread only; destroy it before the context.

#include "crowd/cluster_hierarchy.hpp"
#include "crowd/lod_cut.hpp"
#include "crowd/skinned_model.hpp"
#include "render/occlusion.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace tourmap::render {

class EglContext;

// Table 3.1's three configurations: NoLOD (leaves + frustum culling), VDR, VDR+OC.
enum class RenderMode { no_lod, vdr, vdr_oc };

struct InstanceState {
  int model = 0;                                // from add_model
  crowd::Affine world = crowd::Affine::Identity();  // model -> world (rigid, uniform scale)
  int animation = 0;
  int frame = 0;                                // sampled pose index within the animation
  float tint = 0;                               // 0: model colours; t in (0, 1]: half-mixed with hue t
};

struct FrameRequest {
  crowd::CameraView camera;                     // camera.width/height = output size
  std::vector<InstanceState> instances;
  RenderMode mode = RenderMode::vdr;
  float poe = 0.5f;                             // pixels of error (ignored by no_lod)
  bool heatmap = false;                         // colour clusters by LOD level (Fig. 3.11)
  bool ground = true;                           // ground plane at y = 0 under a sky; false: flat sky colour
};

struct FrameStats {
  std::size_t triangles = 0;                    // drawn (cluster triangles x instances)
  std::size_t clusters_drawn = 0;               // (cluster, instance) pairs drawn
  std::size_t draw_commands = 0;                // indirect commands (one per cluster and pass)
  std::size_t frustum_culled = 0;               // culled subtrees, summed over instances
  std::size_t occluded = 0;                     // cut clusters not drawn because occluded
  std::size_t occlusion_queries = 0;            // boxes tested against the depth buffer
  std::size_t instances_visible = 0;            // instances with at least one cluster drawn
  bool pvs_reset = false;                       // vdr_oc: the PVS started empty this frame
  double lod_cut_ms = 0, render_ms = 0, readback_ms = 0;
};

struct RendererOptions {
  int max_width = 1920, max_height = 1080;
  std::size_t max_instances = 100000;
  CoherenceOptions coherence;
};

// Flat background colour when FrameRequest::ground is false (RGB).
inline constexpr std::uint8_t kSkyRgb[3] = {150, 190, 230};

class CrowdRenderer {
 public:
  explicit CrowdRenderer(EglContext& context, RendererOptions options = {});
  ~CrowdRenderer();
  CrowdRenderer(const CrowdRenderer&) = delete;
  CrowdRenderer& operator=(const CrowdRenderer&) = delete;

  // Uploads a model and its hierarchy (all clusters index the model's original vertices);
  // returns its id for InstanceState::model. Throws std::invalid_argument on inconsistent input.
  int add_model(const crowd::SkinnedModel& model, const crowd::ClusterHierarchy& hierarchy);
  // Frees a model's GPU buffers; its id may be handed out again by add_model. Instances must
  // not name it any more (render() refuses them).
  void remove_model(int model);
  int model_count() const;  // ids handed out so far (removed ones included)
  // Frames of one animation of a model (for callers that advance time).
  int frame_count(int model, int animation) const;

  // Renders and reads back `rgba` (width * height * 4 bytes, rows bottom-up as glReadPixels
  // gives them). Throws std::invalid_argument for a size outside 1x1..max or a bad instance.
  void render(const FrameRequest& request, std::vector<std::uint8_t>& rgba, FrameStats& stats);

  // Forget the PVS (e.g. after a scene change); the next vdr_oc frame tests every cluster.
  void reset_coherence();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tourmap::render
