#pragma once
// One skeleton from the glTF skins used by a scene's mesh nodes, and the mesh-space -> world
// transform that puts the bind pose in the world frame.

#include "crowd/gltf_accessor.hpp"
#include "crowd/gltf_nodes.hpp"

#include <Eigen/Geometry>

#include <vector>

namespace tourmap::crowd::gltf {

struct SkeletonBuild {
  std::vector<int> joint_node;                   // skeleton joint -> node
  std::vector<int> joint_of_node;                // node -> skeleton joint, or -1
  std::vector<Eigen::Matrix4d> inverse_bind;     // the file's B_j^-1 (mesh space -> joint space)
  std::vector<std::vector<int>> skin_joints;     // per skin: skin-local joint -> skeleton joint
  std::vector<Eigen::Matrix4d> skin_correction;  // per skin: C_s with B_{s,j}^-1 = B_j^-1 * C_s
  std::vector<char> skin_used;
};

SkeletonBuild build_skeleton(const ReadContext& ctx, const std::vector<int>& scene);

// Parent joint = nearest ancestor node that is a joint (-1 for a root).
std::vector<int> joint_parents(const NodeGraph& graph, const SkeletonBuild& skeleton);

Eigen::Matrix4d mesh_to_world(const Eigen::Affine3d& root_rest_global, const Eigen::Matrix4d& root_inverse_bind);

}  // namespace tourmap::crowd::gltf
