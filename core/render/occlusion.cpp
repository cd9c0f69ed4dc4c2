#include "occlusion.hpp"

#include "camera.hpp"

#include <algorithm>
#include <cmath>

namespace tourmap::render {
namespace {

constexpr std::uint8_t kVisible = 1;         // visible in frame i-1
constexpr std::uint8_t kAboveVisible = 2;    // an ancestor of a cluster visible in frame i-1

// Calls f(id) for every proper ancestor of `id`, nearest first, until f returns false. The
// walk is capped by the cluster count so a malformed parent chain cannot loop.
template <class F>
void for_ancestors(const crowd::ClusterHierarchy& h, int id, F f) {
  const auto n = h.clusters.size();
  int p = h.clusters[static_cast<std::size_t>(id)].parent;
  for (std::size_t steps = 0; p >= 0 && static_cast<std::size_t>(p) < n && steps < n; ++steps) {
    if (!f(p)) return;
    p = h.clusters[static_cast<std::size_t>(p)].parent;
  }
}

bool valid_id(const crowd::ClusterHierarchy& h, int id) {
  return id >= 0 && static_cast<std::size_t>(id) < h.clusters.size();
}

}  // namespace

void split_by_pvs(const crowd::ClusterHierarchy& h, std::span<const int> visible_last, std::span<const int> cut,
                  std::vector<int>& in_pvs, std::vector<int>& occludees, std::vector<std::uint8_t>& marks) {
  if (marks.size() < h.clusters.size()) marks.resize(h.clusters.size(), 0);
  for (int v : visible_last) {
    if (!valid_id(h, v)) continue;
    marks[static_cast<std::size_t>(v)] |= kVisible;
    for_ancestors(h, v, [&](int a) {
      auto& m = marks[static_cast<std::size_t>(a)];
      if (m & kAboveVisible) return false;  // the rest of the chain is marked already
      m |= kAboveVisible;
      return true;
    });
  }
  for (int c : cut) {
    bool related = valid_id(h, c) && marks[static_cast<std::size_t>(c)] != 0;
    if (!related && valid_id(h, c))
      for_ancestors(h, c, [&](int a) {
        related = (marks[static_cast<std::size_t>(a)] & kVisible) != 0;
        return !related;
      });
    (related ? in_pvs : occludees).push_back(c);
  }
  for (int v : visible_last) {  // leave the scratch zeroed
    if (!valid_id(h, v)) continue;
    marks[static_cast<std::size_t>(v)] = 0;
    for_ancestors(h, v, [&](int a) {
      auto& m = marks[static_cast<std::size_t>(a)];
      if (m == 0) return false;
      m = 0;
      return true;
    });
  }
}

bool FrameCoherence::begin_frame(const crowd::CameraView& view, std::span<const int> instance_models) {
  const crowd::Vec3 direction = view_direction(view);
  bool reset = force_reset_ || frames_since_reset_ >= options_.reset_every_frames ||
               !std::equal(instance_models.begin(), instance_models.end(), models_.begin(), models_.end());
  if (!reset) {
    const float cos_turn = std::clamp(direction.dot(last_direction_), -1.f, 1.f);
    reset = (view.eye - last_eye_).norm() > options_.jump_distance_m || std::acos(cos_turn) > options_.jump_angle_rad;
  }
  last_eye_ = view.eye;
  last_direction_ = direction;
  if (reset) {
    models_.assign(instance_models.begin(), instance_models.end());
    previous_.assign(models_.size(), {});
    current_.assign(models_.size(), {});
    frames_since_reset_ = 0;
    force_reset_ = false;
  }
  ++frames_since_reset_;
  for (auto& c : current_) c.clear();
  return reset;
}

void FrameCoherence::end_frame() { previous_.swap(current_); }

}  // namespace tourmap::render
