#pragma once
// Appends glTF primitives to one merged vertex/index array: positions and normals moved into
// the bind pose, colours, skin influences (remapped into the merged skeleton, validated,
// renormalised) or a rigid weight-1 binding, and indices validated against the primitive.

#include "crowd/gltf_accessor.hpp"
#include "crowd/skinned_model.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace tourmap::crowd::gltf {

struct MergedMesh {
  std::vector<Vec3> positions, normals;
  std::vector<char> has_normal;  // 0: the file had none; computed after merging
  std::vector<std::array<std::uint8_t, 4>> colors;
  std::vector<std::array<std::uint16_t, 4>> joints;
  std::vector<std::array<float, 4>> weights;
  std::vector<std::uint32_t> indices;
  std::size_t skipped_primitives = 0;  // not TRIANGLES, or without POSITION
};

// How one primitive's vertices enter the merged bind pose.
struct Binding {
  Eigen::Matrix4d to_bind = Eigen::Matrix4d::Identity();  // mesh space -> bind-pose space
  const std::vector<int>* skin_joints = nullptr;          // skin-local joint -> skeleton joint; null: rigid
  int rigid_joint = 0;                                    // weight-1 joint of a rigid primitive
};

// Skips (and counts) primitives that are not TRIANGLES or have no POSITION. `what` names the
// primitive in errors. A skinned binding requires JOINTS_0 and WEIGHTS_0 (has_skin_attributes).
void append_primitive(const ReadContext& ctx, const tinygltf::Primitive& primitive, const std::string& what,
                      const Binding& binding, MergedMesh& out);

bool has_skin_attributes(const tinygltf::Primitive& primitive);

}  // namespace tourmap::crowd::gltf
