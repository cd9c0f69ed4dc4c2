// VDR+OC (sec. 3.5.2): the occlusion tests and the three steps of the culled frame.

#include "crowd_renderer_impl.hpp"

#include <algorithm>
#include <cmath>

namespace tourmap::render {
namespace {

using detail::BoxQuery;
using detail::DrawItem;

// Front-to-back batches of the occlusion tests: at most kMaxBatches, one per kInstancesPerBatch
// instances with occludees.
constexpr std::size_t kMaxBatches = 4;
constexpr std::size_t kInstancesPerBatch = 4;

}  // namespace

// Occlusion tests against the current depth buffer (sec. 3.5.2, step 2), colour and depth
// writes off. All boxes are drawn in one instanced draw whose fragments (after the depth test)
// flag their box in a buffer, read back once. One GL query object per box would give the same
// answers, but llvmpipe bins every begin/end query into every screen tile, which made a query
// cost 35-80 us at 1280x720. A box the camera is in (or whose near-plane clipping could hide
// it) is visible untested; boxes are grown slightly so rasterisation rounding stays conservative.
void CrowdRenderer::Impl::test_boxes(const crowd::CameraView& view, std::span<const BoxQuery> boxes,
                                     std::vector<std::uint8_t>& visible, FrameStats& stats) {
  visible.assign(boxes.size(), 1);
  if (boxes.empty()) return;
  const float aspect = static_cast<float>(view.width) / static_cast<float>(view.height);
  const float tan_half = std::tan(view.fov_y_rad * 0.5f);
  // Distance from the eye to a corner of the near-plane rectangle.
  const float near_reach = view.near_m * std::sqrt(1.f + tan_half * tan_half * (1.f + aspect * aspect)) * 1.01f;

  std::vector<std::size_t> tested;
  tested.reserve(boxes.size());
  box_matrices.clear();
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const crowd::Box3& b = *boxes[i].box;
    const crowd::Affine& world = *boxes[i].world;
    if (b.isEmpty()) continue;
    const float scale = std::max(world.linear().colwise().norm().minCoeff(), 1e-12f);
    const crowd::Vec3 grow = crowd::Vec3::Constant(near_reach / scale + 1e-4f * b.diagonal().norm());
    const crowd::Vec3 eye_model = world.inverse(Eigen::Affine) * view.eye;
    if (crowd::Box3(b.min() - grow, b.max() + grow).contains(eye_model)) continue;
    const crowd::Vec3 half = b.sizes() * 0.5f * 1.001f + crowd::Vec3::Constant(1e-5f * b.diagonal().norm());
    // A mirroring world transform would turn the cube inside out for back-face culling; mirror
    // the (symmetric) cube too.
    const float mirror = world.linear().determinant() < 0 ? -1.f : 1.f;
    const Eigen::Affine3f unit_to_model =
        Eigen::Translation3f(b.center()) * Eigen::Scaling(crowd::Vec3(mirror * half.x(), half.y(), half.z()));
    box_matrices.push_back(view.view_proj * (world * unit_to_model).matrix());
    tested.push_back(i);
  }
  if (tested.empty()) return;
  box_matrix_buffer.upload(box_matrices.data(), box_matrices.size() * sizeof(Eigen::Matrix4f));
  glVertexArrayVertexBuffer(box_vao, 1, box_matrix_buffer.id(), 0, sizeof(Eigen::Matrix4f));
  box_flags.assign(tested.size(), 0);
  visibility_buffer.upload(box_flags.data(), box_flags.size() * sizeof(std::uint32_t));

  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_CULL_FACE);
  glUseProgram(box.id());
  glBindVertexArray(box_vao);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, visibility_buffer.id());
  glDrawElementsInstanced(GL_TRIANGLES, 36, GL_UNSIGNED_BYTE, nullptr, static_cast<GLsizei>(tested.size()));
  glDisable(GL_CULL_FACE);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(visibility_buffer.id(), 0, static_cast<GLsizeiptr>(box_flags.size() * sizeof(std::uint32_t)),
                          box_flags.data());
  for (std::size_t t = 0; t < tested.size(); ++t) visible[tested[t]] = box_flags[t] != 0 ? 1 : 0;
  stats.occlusion_queries += tested.size();
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

// VDR+OC (sec. 3.5.2). Step 1: the cut clusters related to last frame's visible set (see
// split_by_pvs) and every cluster of static models (walls, rooms: the occluders) are drawn into
// colour and depth. Step 2: the other cut clusters are tested with occlusion queries of their
// bounding boxes against that depth, hierarchically to keep the query count low: first one
// query per instance with its whole-hierarchy box (only for instances with nothing in the PVS
// and more than one occludee), then one per cluster of the instances not rejected. Step 3: the
// newly visible clusters are drawn and join the PVS. Steps 2 and 3 alternate over front-to-back
// batches of instances. Conservative: a cluster is dropped only when its box is behind depth
// that the final image contains as well.
void CrowdRenderer::Impl::render_with_occlusion_culling(const FrameRequest& request, FrameStats& stats) {
  if (!last_frame_culled_occlusion) coherence.reset();  // the PVS is from an older vdr_oc frame
  std::vector<int> instance_models(request.instances.size());
  for (std::size_t i = 0; i < request.instances.size(); ++i) instance_models[i] = request.instances[i].model;
  stats.pvs_reset = coherence.begin_frame(request.camera, instance_models);

  std::vector<DrawItem> step1, step3;
  std::vector<DrawItem> occludees;
  std::vector<std::size_t> occludee_begin(request.instances.size() + 1, 0);
  std::vector<int> in_pvs, rest;
  for (std::size_t i = 0; i < request.instances.size(); ++i) {
    const GpuModel& model = *models[static_cast<std::size_t>(request.instances[i].model)];
    const std::span<const int> instance_cut(cut.data() + cut_begin[i], cut_begin[i + 1] - cut_begin[i]);
    in_pvs.clear();
    rest.clear();
    if (model.is_static()) {
      in_pvs.assign(instance_cut.begin(), instance_cut.end());
    } else {
      split_by_pvs(model.hierarchy(), coherence.previous(i), instance_cut, in_pvs, rest, marks);
      coherence.current(i) = in_pvs;
    }
    for (int c : in_pvs) step1.push_back({static_cast<int>(i), c});
    for (int c : rest) occludees.push_back({static_cast<int>(i), c});
    occludee_begin[i + 1] = occludees.size();
  }
  draw_items(request, step1, stats);

  // Step 2 runs front to back in a few batches (instances ordered by the distance of their
  // boxes): the newly visible clusters of a batch are drawn before the next batch is tested, so
  // near characters hide far ones even right after a PVS reset, when only static occluders are
  // in the depth buffer. Each batch costs two waits for query results.
  std::vector<std::pair<float, std::size_t>> by_distance;
  for (std::size_t i = 0; i < request.instances.size(); ++i) {
    if (occludee_begin[i + 1] == occludee_begin[i]) continue;
    const GpuModel& model = *models[static_cast<std::size_t>(request.instances[i].model)];
    const crowd::Vec3 centre =
        request.instances[i].world * model.subtree_bounds()[static_cast<std::size_t>(model.hierarchy().root)].center();
    by_distance.push_back({(centre - request.camera.eye).squaredNorm(), i});
  }
  std::sort(by_distance.begin(), by_distance.end());
  const std::size_t batches = std::clamp<std::size_t>(by_distance.size() / kInstancesPerBatch, 1, kMaxBatches);
  // Batch b ends at (2^(b+1) - 1) / (2^batches - 1) of the instances: sizes 1 : 2 : 4 : 8, as the
  // nearest few do most of the occluding.
  const auto batch_end = [&](std::size_t b) {
    return by_distance.begin() +
           static_cast<std::ptrdiff_t>(by_distance.size() * ((std::size_t{1} << b) - 1) / ((std::size_t{1} << batches) - 1));
  };
  std::vector<BoxQuery> boxes;
  std::vector<std::size_t> box_owner;
  std::vector<std::uint8_t> visible;
  for (std::size_t batch = 0; batch < batches; ++batch) {
    const auto first = batch_end(batch), last = batch_end(batch + 1);
    // Step 2a: one query for the whole hierarchy box of each instance with nothing in the PVS.
    boxes.clear();
    box_owner.clear();
    for (auto it = first; it != last; ++it) {
      const std::size_t i = it->second;
      const std::size_t n = occludee_begin[i + 1] - occludee_begin[i];
      const bool has_pvs = n < cut_begin[i + 1] - cut_begin[i];
      if (n > 1 && !has_pvs) {
        const GpuModel& model = *models[static_cast<std::size_t>(request.instances[i].model)];
        boxes.push_back({&model.subtree_bounds()[static_cast<std::size_t>(model.hierarchy().root)], &request.instances[i].world});
        box_owner.push_back(i);
      }
    }
    test_boxes(request.camera, boxes, visible, stats);
    std::vector<std::uint8_t> instance_hidden(request.instances.size(), 0);
    for (std::size_t b = 0; b < boxes.size(); ++b) instance_hidden[box_owner[b]] = visible[b] ? 0 : 1;

    // Step 2b: one query per occludee cluster of the instances not rejected whole.
    boxes.clear();
    box_owner.clear();
    for (auto it = first; it != last; ++it) {
      const std::size_t i = it->second;
      if (instance_hidden[i]) {
        stats.occluded += occludee_begin[i + 1] - occludee_begin[i];
        continue;
      }
      const GpuModel& model = *models[static_cast<std::size_t>(request.instances[i].model)];
      for (std::size_t k = occludee_begin[i]; k < occludee_begin[i + 1]; ++k) {
        boxes.push_back({&model.hierarchy().clusters[static_cast<std::size_t>(occludees[k].cluster)].bounds,
                         &request.instances[i].world});
        box_owner.push_back(k);
      }
    }
    test_boxes(request.camera, boxes, visible, stats);
    // Step 3: draw the newly visible clusters; they join the PVS.
    step3.clear();
    for (std::size_t b = 0; b < boxes.size(); ++b) {
      const DrawItem& d = occludees[box_owner[b]];
      if (visible[b]) {
        step3.push_back(d);
        coherence.current(static_cast<std::size_t>(d.instance)).push_back(d.cluster);
      } else {
        ++stats.occluded;
      }
    }
    draw_items(request, step3, stats);
  }
  coherence.end_frame();
}

}  // namespace tourmap::render
