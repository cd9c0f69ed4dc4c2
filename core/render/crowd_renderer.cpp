#include "crowd_renderer_impl.hpp"

#include "egl_context.hpp"
#include "util/elapsed.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

namespace tourmap::render {
namespace {

using detail::DrawCommand;
using detail::DrawItem;
using detail::GpuInstance;
using detail::GpuItem;

using util::Clock;
using util::ms_since;

const crowd::Vec3 kLightDirection = crowd::Vec3(0.35f, 1.0f, 0.45f).normalized();

}  // namespace

CrowdRenderer::Impl::Impl(EglContext& context_in, RendererOptions options_in)
    : context(context_in), options(options_in), coherence(options_in.coherence) {
  scene_view_proj = scene.uniform("u_view_proj");
  scene_single_joint = scene.uniform("u_single_joint");
  scene_flat = scene.uniform("u_flat");
  scene_heatmap = scene.uniform("u_heatmap");
  scene_eye = scene.uniform("u_eye");
  scene_light = scene.uniform("u_light_dir");
  background_view_proj = background.uniform("u_view_proj");
  background_inverse = background.uniform("u_inv_view_proj");

  glCreateVertexArrays(1, &empty_vao);
  // The query proxy: a cube [-1, 1]^3, 12 triangles.
  const float corners[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                               {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  // Counter-clockwise seen from outside: the box pass culls back faces (half the fragments).
  const std::uint8_t faces[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 5, 4, 0, 1, 5,
                                  3, 6, 2, 3, 7, 6, 0, 7, 3, 0, 4, 7, 1, 6, 5, 1, 2, 6};
  glCreateBuffers(1, &box_vertices);
  glNamedBufferStorage(box_vertices, sizeof corners, corners, 0);
  glCreateBuffers(1, &box_indices);
  glNamedBufferStorage(box_indices, sizeof faces, faces, 0);
  glCreateVertexArrays(1, &box_vao);
  glVertexArrayVertexBuffer(box_vao, 0, box_vertices, 0, 3 * sizeof(float));
  glVertexArrayElementBuffer(box_vao, box_indices);
  glEnableVertexArrayAttrib(box_vao, 0);
  glVertexArrayAttribFormat(box_vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(box_vao, 0, 0);
  for (GLuint column = 0; column < 4; ++column) {  // mat4 a_box_to_clip at locations 1..4
    glEnableVertexArrayAttrib(box_vao, 1 + column);
    glVertexArrayAttribFormat(box_vao, 1 + column, 4, GL_FLOAT, GL_FALSE, column * 4 * sizeof(float));
    glVertexArrayAttribBinding(box_vao, 1 + column, 1);
  }
  glVertexArrayBindingDivisor(box_vao, 1, 1);
  check_gl("CrowdRenderer setup");
}

CrowdRenderer::Impl::~Impl() {
  models.clear();
  glDeleteFramebuffers(1, &framebuffer);
  const GLuint renderbuffers[] = {color_buffer, depth_buffer};
  glDeleteRenderbuffers(2, renderbuffers);
  const GLuint arrays[] = {empty_vao, box_vao};
  glDeleteVertexArrays(2, arrays);
  const GLuint buffers[] = {box_vertices, box_indices};
  glDeleteBuffers(2, buffers);
}

void CrowdRenderer::Impl::validate(const FrameRequest& request) const {
  const crowd::CameraView& cam = request.camera;
  if (cam.width < 1 || cam.height < 1 || cam.width > options.max_width || cam.height > options.max_height)
    throw std::invalid_argument("CrowdRenderer: frame size " + std::to_string(cam.width) + "x" +
                                std::to_string(cam.height) + " is outside 1x1.." + std::to_string(options.max_width) +
                                "x" + std::to_string(options.max_height));
  if (!cam.view_proj.allFinite() || !cam.eye.allFinite())
    throw std::invalid_argument("CrowdRenderer: the camera has non-finite values");
  if (!(cam.fov_y_rad > 0 && cam.fov_y_rad < 3.14159f) || !(cam.near_m > 0 && cam.far_m > cam.near_m))
    throw std::invalid_argument("CrowdRenderer: the camera needs 0 < fov_y < pi and 0 < near < far");
  if (request.mode != RenderMode::no_lod && !(request.poe >= 0 && std::isfinite(request.poe)))
    throw std::invalid_argument("CrowdRenderer: poe must be finite and >= 0");
  if (request.instances.size() > options.max_instances)
    throw std::invalid_argument("CrowdRenderer: " + std::to_string(request.instances.size()) +
                                " instances, at most " + std::to_string(options.max_instances));
  for (std::size_t i = 0; i < request.instances.size(); ++i) {
    const InstanceState& inst = request.instances[i];
    const std::string which = "CrowdRenderer: instance " + std::to_string(i) + ": ";
    if (inst.model < 0 || static_cast<std::size_t>(inst.model) >= models.size() ||
        !models[static_cast<std::size_t>(inst.model)])
      throw std::invalid_argument(which + "no model " + std::to_string(inst.model));
    if (!inst.world.matrix().allFinite() || !std::isfinite(inst.tint))
      throw std::invalid_argument(which + "non-finite world transform or tint");
    try {
      models[static_cast<std::size_t>(inst.model)]->palette_base(inst.animation, inst.frame);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(which + e.what());
    }
  }
}

void CrowdRenderer::Impl::ensure_framebuffer(int width, int height) {
  if (framebuffer != 0 && width == framebuffer_width && height == framebuffer_height) return;
  glDeleteFramebuffers(1, &framebuffer);
  const GLuint old[] = {color_buffer, depth_buffer};
  glDeleteRenderbuffers(2, old);
  glCreateRenderbuffers(1, &color_buffer);
  glNamedRenderbufferStorage(color_buffer, GL_RGBA8, width, height);
  glCreateRenderbuffers(1, &depth_buffer);
  glNamedRenderbufferStorage(depth_buffer, GL_DEPTH_COMPONENT24, width, height);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferRenderbuffer(framebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_buffer);
  glNamedFramebufferRenderbuffer(framebuffer, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer);
  if (glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("CrowdRenderer: the " + std::to_string(width) + "x" + std::to_string(height) +
                             " framebuffer is incomplete");
  framebuffer_width = width;
  framebuffer_height = height;
}

void CrowdRenderer::Impl::draw_background(const FrameRequest& request) {
  if (request.ground) {
    glClearColor(0, 0, 0, 1);
  } else {
    glClearColor(kSkyRgb[0] / 255.f, kSkyRgb[1] / 255.f, kSkyRgb[2] / 255.f, 1.f);
  }
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (!request.ground) return;
  const Eigen::Matrix4f inverse = request.camera.view_proj.inverse();
  if (!inverse.allFinite()) throw std::invalid_argument("CrowdRenderer: the camera's view_proj is singular");
  glUseProgram(background.id());
  glUniformMatrix4fv(background_view_proj, 1, GL_FALSE, request.camera.view_proj.data());
  glUniformMatrix4fv(background_inverse, 1, GL_FALSE, inverse.data());
  glDepthFunc(GL_ALWAYS);  // the sky writes depth 1.0, which GL_LESS would reject
  glBindVertexArray(empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthFunc(GL_LESS);
}

// Instancing (sec. 3.5.2, "Instancing and static models"): the (instance, cluster) pairs are
// grouped by cluster with a counting sort, so a cluster drawn for k instances is one indirect
// command with instanceCount k whose baseInstance points at its k items; neighbouring clusters in
// the index buffer drawn for the same items share a command; one multi-draw per model.
void CrowdRenderer::Impl::draw_items(const FrameRequest& request, std::span<const DrawItem> draw, FrameStats& stats) {
  if (draw.empty()) return;
  const std::size_t keys = model_first_key.back();
  key_count.assign(keys + 1, 0);
  const auto key_of = [&](const DrawItem& d) {
    return model_first_key[static_cast<std::size_t>(request.instances[static_cast<std::size_t>(d.instance)].model)] +
           static_cast<std::size_t>(d.cluster);
  };
  for (const DrawItem& d : draw) ++key_count[key_of(d)];
  key_next.assign(keys + 1, 0);
  for (std::size_t k = 0; k < keys; ++k) key_next[k + 1] = key_next[k] + key_count[k];
  items.resize(draw.size());
  for (const DrawItem& d : draw) {
    const GpuModel& m = *models[static_cast<std::size_t>(request.instances[static_cast<std::size_t>(d.instance)].model)];
    const auto fineness = static_cast<std::uint32_t>(std::lround(m.fineness()[static_cast<std::size_t>(d.cluster)] * 255.f));
    items[key_next[key_of(d)]++] = {static_cast<std::uint32_t>(d.instance), fineness};
    instance_drawn[static_cast<std::size_t>(d.instance)] = 1;
  }
  commands.clear();
  std::vector<std::pair<std::size_t, std::size_t>> model_commands(models.size());  // [begin, end)
  for (std::size_t m = 0; m < models.size(); ++m) {
    model_commands[m].first = model_commands[m].second = commands.size();
    if (!models[m]) continue;  // removed
    const auto& clusters = models[m]->hierarchy().clusters;
    for (int id : models[m]->clusters_in_index_order()) {
      const auto c = static_cast<std::size_t>(id);
      const std::size_t key = model_first_key[m] + c;
      const std::uint32_t k = key_count[key];
      if (k == 0) continue;
      stats.clusters_drawn += k;
      stats.triangles += std::size_t{k} * clusters[c].triangle_count();
      if (clusters[c].index_count == 0) continue;
      const std::uint32_t first_item = key_next[key] - k;  // key_next now holds each key's end
      // A cluster right after the previous command's triangles, drawn for the same items
      // (instances and LOD colour), extends that command instead of adding one.
      if (commands.size() > model_commands[m].first) {
        DrawCommand& last = commands.back();
        if (last.first_index + last.count == clusters[c].first_index && last.instance_count == k &&
            std::equal(items.begin() + last.base_instance, items.begin() + last.base_instance + k,
                       items.begin() + first_item, [](const GpuItem& a, const GpuItem& b) {
                         return a.instance == b.instance && a.fineness == b.fineness;
                       })) {
          last.count += clusters[c].index_count;
          continue;
        }
      }
      commands.push_back({clusters[c].index_count, k, clusters[c].first_index, 0, first_item});
    }
    model_commands[m].second = commands.size();
  }
  stats.draw_commands += commands.size();
  item_buffer.upload(items.data(), items.size() * sizeof(GpuItem));
  command_buffer.upload(commands.data(), commands.size() * sizeof(DrawCommand));

  glUseProgram(scene.id());
  glUniformMatrix4fv(scene_view_proj, 1, GL_FALSE, request.camera.view_proj.data());
  glUniform1i(scene_heatmap, request.heatmap ? 1 : 0);
  glUniform3fv(scene_eye, 1, request.camera.eye.data());
  glUniform3fv(scene_light, 1, kLightDirection.data());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, instance_buffer.id());
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, command_buffer.id());
  for (std::size_t m = 0; m < models.size(); ++m) {
    const auto [begin, end] = model_commands[m];
    if (begin == end) continue;
    const GpuModel& model = *models[m];
    glBindVertexArray(model.vertex_array());
    glVertexArrayVertexBuffer(model.vertex_array(), kItemBinding, item_buffer.id(), 0, sizeof(GpuItem));
    glBindTextureUnit(0, model.palette_texture());
    glUniform1i(scene_single_joint, model.joint_count() == 1 ? 1 : 0);
    glUniform1i(scene_flat, model.is_static() ? 1 : 0);
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                                reinterpret_cast<const void*>(begin * sizeof(DrawCommand)),
                                static_cast<GLsizei>(end - begin), sizeof(DrawCommand));
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

void CrowdRenderer::Impl::render(const FrameRequest& request, std::vector<std::uint8_t>& rgba, FrameStats& stats) {
  stats = {};
  validate(request);
  const std::size_t n = request.instances.size();

  // LOD cut with view-frustum culling per instance (sec. 3.5.1); NoLOD is the leaf cut.
  const auto t_cut = Clock::now();
  const float poe = request.mode == RenderMode::no_lod ? 0.f : request.poe;
  cut_input.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const InstanceState& inst = request.instances[i];
    cut_input[i] = {&models[static_cast<std::size_t>(inst.model)]->cut_tree(), &inst.world};
  }
  crowd::CutStats cut_stats;
  crowd::cut_instances(cut_input, request.camera, poe, &cut_threads, cut_workspace, cut, cut_begin, cut_stats);
  stats.frustum_culled += cut_stats.frustum_culled;
  stats.lod_cut_ms = ms_since(t_cut);

  const auto t_render = Clock::now();
  context.make_current();
  ensure_framebuffer(request.camera.width, request.camera.height);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, request.camera.width, request.camera.height);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDepthFunc(GL_LESS);
  draw_background(request);

  gpu_instances.resize(std::max<std::size_t>(n, 1));
  for (std::size_t i = 0; i < n; ++i) {
    const InstanceState& inst = request.instances[i];
    GpuInstance& g = gpu_instances[i];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) g.world_rows[r * 4 + c] = inst.world.matrix()(r, c);
    g.palette_base = models[static_cast<std::size_t>(inst.model)]->palette_base(inst.animation, inst.frame);
    g.tint = inst.tint;
    g.pad[0] = g.pad[1] = 0;
  }
  instance_buffer.upload(gpu_instances.data(), gpu_instances.size() * sizeof(GpuInstance));
  instance_drawn.assign(n, 0);

  if (request.mode == RenderMode::vdr_oc) {
    render_with_occlusion_culling(request, stats);
    last_frame_culled_occlusion = true;
  } else {
    std::vector<DrawItem> all(cut.size());
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = cut_begin[i]; k < cut_begin[i + 1]; ++k) all[k] = {static_cast<int>(i), cut[k]};
    draw_items(request, all, stats);
    last_frame_culled_occlusion = false;
  }
  stats.instances_visible = static_cast<std::size_t>(std::count(instance_drawn.begin(), instance_drawn.end(), 1));
  glFinish();
  check_gl("CrowdRenderer::render");
  stats.render_ms = ms_since(t_render);

  const auto t_read = Clock::now();
  rgba.resize(static_cast<std::size_t>(request.camera.width) * static_cast<std::size_t>(request.camera.height) * 4);
  glNamedFramebufferReadBuffer(framebuffer, GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, request.camera.width, request.camera.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  check_gl("CrowdRenderer readback");
  stats.readback_ms = ms_since(t_read);
}

CrowdRenderer::CrowdRenderer(EglContext& context, RendererOptions options) {
  context.make_current();
  impl_ = std::make_unique<Impl>(context, options);
}

CrowdRenderer::~CrowdRenderer() {
  impl_->context.make_current();
  impl_.reset();
}

int CrowdRenderer::add_model(const crowd::SkinnedModel& model, const crowd::ClusterHierarchy& hierarchy) {
  impl_->context.make_current();
  auto gpu = std::make_unique<GpuModel>(model, hierarchy);
  impl_->coherence.reset();
  // A removed model's slot is re-used when its range of cluster keys is big enough, so that
  // models added and removed over and over (scene variants) do not grow the key space.
  auto& keys = impl_->model_first_key;
  for (std::size_t m = 0; m < impl_->models.size(); ++m)
    if (!impl_->models[m] && keys[m + 1] - keys[m] >= hierarchy.clusters.size()) {
      impl_->models[m] = std::move(gpu);
      return static_cast<int>(m);
    }
  impl_->models.push_back(std::move(gpu));
  if (keys.empty()) keys.push_back(0);
  keys.push_back(keys.back() + hierarchy.clusters.size());
  return static_cast<int>(impl_->models.size()) - 1;
}

void CrowdRenderer::remove_model(int model) {
  if (model < 0 || model >= model_count() || !impl_->models[static_cast<std::size_t>(model)])
    throw std::invalid_argument("CrowdRenderer: no model " + std::to_string(model));
  impl_->context.make_current();
  impl_->models[static_cast<std::size_t>(model)].reset();  // frees its buffers and texture
  impl_->coherence.reset();
}

int CrowdRenderer::model_count() const { return static_cast<int>(impl_->models.size()); }

int CrowdRenderer::frame_count(int model, int animation) const {
  if (model < 0 || model >= model_count() || !impl_->models[static_cast<std::size_t>(model)]) throw std::invalid_argument("CrowdRenderer: no model " + std::to_string(model));
  return impl_->models[static_cast<std::size_t>(model)]->frame_count(animation);
}

void CrowdRenderer::render(const FrameRequest& request, std::vector<std::uint8_t>& rgba, FrameStats& stats) {
  impl_->render(request, rgba, stats);
}

void CrowdRenderer::reset_coherence() { impl_->coherence.reset(); }

}  // namespace tourmap::render
