#pragma once
// A skinned character (or a static mesh) as plain arrays, ready for linear blend skinning
// (eq. 3.1) on the CPU or in a vertex shader. All glTF primitives of a model are merged into
// one vertex/index array; a static mesh is a model with one identity joint and one pose.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tourmap::crowd {

using Vec3 = Eigen::Vector3f;
using Box3 = Eigen::AlignedBox3f;
// Rigid transforms are kept as 3x4 (rotation/scale | translation); the last row is implied.
using Affine = Eigen::Affine3f;

struct Skeleton {
  std::vector<std::string> joint_names;
  std::vector<int> parent;             // index into the joints, -1 for a root
  std::vector<Eigen::Matrix4f> inverse_bind;
};

// One sampled pose: per joint, the skinning matrix M_j = G_j * B_j^-1 (global joint transform
// times inverse bind matrix), mapping bind-pose mesh space to posed model space (eq. 3.1).
// `global` keeps G_j itself (deformation levels need the bone frames).
struct Pose {
  std::vector<Affine> skinning;
  std::vector<Affine> global;
};

struct Animation {
  std::string name;
  float duration_s = 0;
  float fps = 30;                      // poses are sampled at t = k / fps, k = 0..n-1
  std::vector<Pose> poses;
};

struct SkinnedModel {
  std::string name;
  // Vertices (bind pose, glTF mesh space; metres, +Y up after the loader's node transforms).
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<std::array<std::uint8_t, 4>> colors;   // RGBA base colour (material/texture average)
  std::vector<std::array<std::uint16_t, 4>> joints;  // up to 4 influences per vertex
  std::vector<std::array<float, 4>> weights;         // sum to 1
  std::vector<std::uint32_t> indices;                // triangles
  Skeleton skeleton;
  std::vector<Animation> animations;  // a static mesh has one animation with one identity pose

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return indices.size() / 3; }
  bool is_static() const { return skeleton.parent.size() <= 1 && animations.size() == 1 &&
                                   animations[0].poses.size() == 1; }
};

}  // namespace tourmap::crowd
