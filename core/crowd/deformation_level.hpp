#pragma once
// Deformation level of each vertex (sec. 3.4.2): how much the vertex moves during the animations
// relative to the least common ancestor b_a of the bones that influence it, measured as the
// diagonal of the bounding box of its trajectory in b_a's frame (Pose::global[b_a]^-1 applied to
// the skinned position, times the frame's uniform scale so the level is in model units). It stands in for the vertex's
// simplification error when the clusters are formed (before anything is simplified).

#include "crowd/skinned_model.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace tourmap::crowd {

// The least common ancestor in the skeleton of the joints with weight > 0, or -1 when there is
// none (no influence, or influences in different trees of a skeleton forest); -1 means the model
// frame is used.
int influence_ancestor(const Skeleton& skeleton, const std::array<std::uint16_t, 4>& joints,
                       const std::array<float, 4>& weights);

struct VertexTrajectories {
  std::vector<float> deformation_level;  // per vertex, model units (sec. 3.4.2)
  std::vector<Box3> bounds;              // per vertex: bbox of its skinned position over all poses
};

// One pass over every sampled pose of every animation. A model without poses (or a static
// model) gets level 0 and its bind position as bounds. Throws std::invalid_argument on a pose
// whose matrix counts do not match the skeleton.
VertexTrajectories vertex_trajectories(const SkinnedModel& model);

std::vector<float> deformation_levels(const SkinnedModel& model);

}  // namespace tourmap::crowd
