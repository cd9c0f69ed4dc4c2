#pragma once
// CPU side of the conservative occlusion culling with frame-to-frame coherence (sec. 3.5.2):
// which clusters of the current LOD cut are in the potentially visible set (PVS), and when the
// PVS kept from the previous frame is thrown away. The GL side (occlusion map, queries) is in
// crowd_renderer.cpp.

#include "crowd/cluster_hierarchy.hpp"
#include "crowd/lod_cut.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace tourmap::render {

// Step 1 of sec. 3.5.2 ("update PVS_{i-1} to the current cut"): a cluster c of the current cut
// is in PVS_i when c itself, an ancestor of c (the cut was refined below it) or a descendant of c
// (the cut was coarsened above it) was visible in frame i-1. Every other cut cluster is a
// potential occludee and goes to the occlusion queries. Ids in `visible_last` outside the
// hierarchy are ignored. `marks` is scratch space (cluster count bytes, left all zero).
void split_by_pvs(const crowd::ClusterHierarchy& h, std::span<const int> visible_last, std::span<const int> cut,
                  std::vector<int>& in_pvs, std::vector<int>& occludees, std::vector<std::uint8_t>& marks);

struct CoherenceOptions {
  int reset_every_frames = 20;     // n: the PVS is emptied every n frames (sec. 3.5.2)
  float jump_distance_m = 1.0f;    // the camera moved farther than this since the last frame ...
  float jump_angle_rad = 0.2618f;  // ... or turned more than this (15 degrees): reset
};

// The per-instance PVS across frames. Instances are identified by their index in the frame
// request; a change in the instance list (count or model of an instance) resets everything.
// A stale PVS costs speed only, never correctness: clusters outside it are tested.
class FrameCoherence {
 public:
  explicit FrameCoherence(CoherenceOptions options = {}) : options_(options) {}

  // Starts a frame; returns true when the PVS was reset (every n frames, a camera jump, a new
  // instance list, or reset() since the last frame). Then previous(i) is PVS_{i-1} of instance i
  // and current(i) is empty, to be filled with PVS_i.
  bool begin_frame(const crowd::CameraView& view, std::span<const int> instance_models);
  const std::vector<int>& previous(std::size_t instance) const { return previous_[instance]; }
  std::vector<int>& current(std::size_t instance) { return current_[instance]; }
  // PVS_i becomes the previous set of the next frame.
  void end_frame();
  void reset() { force_reset_ = true; }

  const CoherenceOptions& options() const { return options_; }

 private:
  CoherenceOptions options_;
  std::vector<std::vector<int>> previous_, current_;
  std::vector<int> models_;
  crowd::Vec3 last_eye_ = crowd::Vec3::Zero();
  crowd::Vec3 last_direction_ = crowd::Vec3::Zero();
  int frames_since_reset_ = 0;
  bool force_reset_ = true;
};

}  // namespace tourmap::render
