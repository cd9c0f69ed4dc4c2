#pragma once
// Internals of CrowdRenderer shared by its two source files: crowd_renderer.cpp (setup, LOD
// cut, instanced drawing, readback) and occlusion_pass.cpp (VDR+OC, sec. 3.5.2).

#include "crowd_renderer.hpp"
#include "crowd/cut_instances.hpp"
#include "crowd_shaders.hpp"
#include "gl_program.hpp"
#include "gpu_model.hpp"
#include "occlusion.hpp"
#include "util/fork_join.hpp"

#include <Eigen/Core>

#include <memory>
#include <span>
#include <vector>

namespace tourmap::render {
namespace detail {

// std430 layout of `Instance` in the scene vertex shader.
struct GpuInstance {
  float world_rows[12];
  std::uint32_t palette_base;
  float tint;
  float pad[2];
};
static_assert(sizeof(GpuInstance) == 64);

// The per-draw item read through the instanced attribute (divisor 1).
struct GpuItem {
  std::uint32_t instance;
  std::uint32_t fineness;  // 0 (root) .. 255 (leaf)
};

// glMultiDrawElementsIndirect's command layout.
struct DrawCommand {
  GLuint count;
  GLuint instance_count;
  GLuint first_index;
  GLint base_vertex;
  GLuint base_instance;
};

// One cluster of one instance.
struct DrawItem {
  int instance;
  int cluster;
};

// A box for an occlusion query: model-space bounds placed by an instance's world transform.
struct BoxQuery {
  const crowd::Box3* box;
  const crowd::Affine* world;
};

}  // namespace detail

struct CrowdRenderer::Impl {
  Impl(EglContext& context, RendererOptions options);
  ~Impl();

  void render(const FrameRequest& request, std::vector<std::uint8_t>& rgba, FrameStats& stats);
  void validate(const FrameRequest& request) const;
  void ensure_framebuffer(int width, int height);
  void draw_background(const FrameRequest& request);
  void draw_items(const FrameRequest& request, std::span<const detail::DrawItem> draw, FrameStats& stats);
  void test_boxes(const crowd::CameraView& view, std::span<const detail::BoxQuery> boxes,
                  std::vector<std::uint8_t>& visible, FrameStats& stats);
  void render_with_occlusion_culling(const FrameRequest& request, FrameStats& stats);

  EglContext& context;
  RendererOptions options;
  std::vector<std::unique_ptr<GpuModel>> models;
  std::vector<std::size_t> model_first_key;  // prefix sum of cluster counts: (model, cluster) -> key
  GlProgram scene{"scene", shaders::kSceneVertex, shaders::kSceneFragment};
  GlProgram background{"background", shaders::kBackgroundVertex, shaders::kBackgroundFragment};
  GlProgram box{"occlusion box", shaders::kBoxVertex, shaders::kBoxFragment};
  GLint scene_view_proj = -1, scene_single_joint = -1, scene_flat = -1, scene_heatmap = -1, scene_eye = -1,
        scene_light = -1;
  GLint background_view_proj = -1, background_inverse = -1;
  GLuint framebuffer = 0, color_buffer = 0, depth_buffer = 0;
  int framebuffer_width = 0, framebuffer_height = 0;
  GLuint empty_vao = 0, box_vao = 0, box_vertices = 0, box_indices = 0;
  StreamBuffer instance_buffer, item_buffer, command_buffer, box_matrix_buffer, visibility_buffer;
  FrameCoherence coherence;
  bool last_frame_culled_occlusion = false;

  // Per-frame scratch, kept to avoid reallocating.
  std::vector<detail::GpuInstance> gpu_instances;
  // Threads of the LOD cut (crowd::cut_instances; the cut is the same for any count). One: on
  // this shared 2-core machine (llvmpipe and other streams busy) a second thread measured slower,
  // p50 0.26 vs 0.22 ms and p99 ~5.5 vs ~0.35 ms for 1,000 characters (bench/crowd_bench section
  // 3): the wake-up costs more than the walk it shares, and a preempted helper stalls the frame.
  static constexpr int kCutThreads = 1;
  util::ForkJoin cut_threads{kCutThreads};
  crowd::CutWorkspace cut_workspace;
  std::vector<crowd::CutInstance> cut_input;
  std::vector<int> cut;                    // all instances' cuts, back to back
  std::vector<std::size_t> cut_begin;      // instance i's cut is [cut_begin[i], cut_begin[i + 1])
  std::vector<std::uint32_t> key_count, key_next;
  std::vector<detail::GpuItem> items;
  std::vector<detail::DrawCommand> commands;
  std::vector<std::uint8_t> instance_drawn;
  std::vector<std::uint8_t> marks;
  std::vector<Eigen::Matrix4f> box_matrices;
  std::vector<std::uint32_t> box_flags;
};

}  // namespace tourmap::render
