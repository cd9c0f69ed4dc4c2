#pragma once
// glTF 2.0 (.glb or .gltf) -> SkinnedModel: every TRIANGLES primitive of every mesh node of the
// default scene merged into one vertex/index array, the skins' joints merged into one skeleton,
// and every animation sampled at a fixed rate into skinning matrices M_j = G_j * B_j^-1 (eq. 3.1).
// Everything ends up in the file's world frame (+Y up, metres by glTF convention): bind-pose
// positions are the world rest pose, and skinning matrices map them to the world posed frame.
// Throws tourmap::load::LoadError naming the file and the problem on any bad input.

#include "crowd/skinned_model.hpp"

#include <string>
#include <vector>

namespace tourmap::crowd {

struct LoadOptions {
  float sample_fps = 30;                // poses per second of animation (at least 2 per clip)
  bool weld = true;                     // merge vertices at equal positions with equal skinning,
                                        // so the mesh is connected across UV/normal seams
  std::vector<std::string> animations;  // clip names to keep; empty = all
};

// Requires a skin ("<file>: has no skin ..." otherwise).
SkinnedModel load_skinned_model(const std::string& path, const LoadOptions& options = {});

// Any mesh file: positions in the world frame of the rest pose, one identity joint,
// one animation with one identity pose (SkinnedModel::is_static()).
SkinnedModel load_static_model(const std::string& path, const LoadOptions& options = {});

// Bounding box of the skinned vertices over every sampled pose of every animation.
Box3 posed_bounds(const SkinnedModel& model);

}  // namespace tourmap::crowd
