#pragma once
// Topology of a skinned mesh for clustering and simplification (sec. 3.4.2, 3.4.3), without
// changing the model: glTF meshes often duplicate a vertex along UV/normal seams (Fox.glb is not
// indexed at all), which would cut the surface into islands. The loader welds by default
// (weld.hpp); this is the read-only equivalent for models that were not welded, so clustering
// and simplification see one surface while every cluster keeps the original vertex ids. Copies
// must have the same bind-pose position and the same joint influences, so they move identically
// in every pose and treating them as one vertex can never open a crack.

#include "crowd/skinned_model.hpp"

#include <cstdint>
#include <vector>

namespace tourmap::crowd {

// canonical[v] = the smallest vertex id with v's position and influences (canonical[c] == c).
std::vector<std::uint32_t> canonical_vertices(const SkinnedModel& model);

// Throws std::invalid_argument naming the first inconsistency the clustering code relies on:
// index count not a multiple of 3, index out of range, joints/weights arrays of the wrong
// size, joint index out of range, a skeleton parent out of range or a cycle in it.
void require_consistent_mesh(const SkinnedModel& model);

}  // namespace tourmap::crowd
