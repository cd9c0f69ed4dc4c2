#include "crowd/gltf_skeleton.hpp"

#include "load/load_error.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tourmap::crowd::gltf {
namespace {

using Mat4d = Eigen::Matrix4d;

[[noreturn]] void fail(const std::string& file, const std::string& problem) { throw load::LoadError(file, problem); }

}  // namespace

// The joints of every skin used by a scene mesh node, merged into one skeleton. Skins that
// share joints (RobotExpressive: 4 skins over the same 43 joints) must agree on the inverse bind
// matrices up to one per-skin matrix C_s, which is then applied to that skin's vertices.
SkeletonBuild build_skeleton(const ReadContext& ctx, const std::vector<int>& scene) {
  const auto& m = ctx.model;
  SkeletonBuild sk;
  sk.joint_of_node.assign(m.nodes.size(), -1);
  sk.skin_joints.resize(m.skins.size());
  sk.skin_correction.assign(m.skins.size(), Mat4d::Identity());
  sk.skin_used.assign(m.skins.size(), 0);
  for (int n : scene) {
    const tinygltf::Node& node = m.nodes[static_cast<std::size_t>(n)];
    if (node.mesh < 0 || node.skin < 0) continue;
    if (static_cast<std::size_t>(node.skin) >= m.skins.size())
      fail(ctx.file, "node " + std::to_string(n) + " uses skin " + std::to_string(node.skin) + " that does not exist");
    sk.skin_used[static_cast<std::size_t>(node.skin)] = 1;
  }
  if (std::find(sk.skin_used.begin(), sk.skin_used.end(), 1) == sk.skin_used.end())
    fail(ctx.file, "has a skin, but no mesh node of its scene uses it");

  for (std::size_t s = 0; s < m.skins.size(); ++s) {
    if (!sk.skin_used[s]) continue;
    const tinygltf::Skin& skin = m.skins[s];
    const std::string what = "skin " + std::to_string(s);
    if (skin.joints.empty()) fail(ctx.file, what + " has no joints");
    std::vector<Mat4d> ibm(skin.joints.size(), Mat4d::Identity());
    if (skin.inverseBindMatrices >= 0) {
      const FloatAccessor a = read_floats(ctx, skin.inverseBindMatrices, what + " inverseBindMatrices", {16});
      if (a.count < skin.joints.size())
        fail(ctx.file, what + " has " + std::to_string(a.count) + " inverse bind matrices for " +
                           std::to_string(skin.joints.size()) + " joints");
      for (std::size_t j = 0; j < skin.joints.size(); ++j)
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) ibm[j](r, c) = a.at(j, c * 4 + r);  // column-major
    }
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      const int node = skin.joints[j];
      if (node < 0 || static_cast<std::size_t>(node) >= m.nodes.size())
        fail(ctx.file,
             what + " joint " + std::to_string(j) + " is node " + std::to_string(node) + ", which does not exist");
      if (std::abs(ibm[j].topLeftCorner<3, 3>().determinant()) < 1e-18 ||
          (ibm[j].row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-6)
        fail(ctx.file, what + " joint " + std::to_string(j) + " has a singular or non-affine inverse bind matrix");
    }
    // C_s from the first joint an earlier skin already bound (identity if none is shared).
    for (std::size_t j = 0; j < skin.joints.size(); ++j)
      if (const int joint = sk.joint_of_node[static_cast<std::size_t>(skin.joints[j])]; joint >= 0) {
        sk.skin_correction[s] = sk.inverse_bind[static_cast<std::size_t>(joint)].inverse() * ibm[j];
        break;
      }
    const Mat4d correction_inverse = sk.skin_correction[s].inverse();
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      const int node = skin.joints[j];
      int& joint = sk.joint_of_node[static_cast<std::size_t>(node)];
      if (joint < 0) {  // first skin to list this node
        joint = static_cast<int>(sk.joint_node.size());
        sk.joint_node.push_back(node);
        sk.inverse_bind.push_back(ibm[j] * correction_inverse);
      } else {
        const Mat4d expect = sk.inverse_bind[static_cast<std::size_t>(joint)] * sk.skin_correction[s];
        if ((expect - ibm[j]).cwiseAbs().maxCoeff() > 1e-4 * std::max(1.0, ibm[j].cwiseAbs().maxCoeff()))
          fail(ctx.file, what + " binds joint '" + m.nodes[static_cast<std::size_t>(node)].name +
                             "' differently from an earlier skin (skins of one model must share one bind pose)");
      }
      sk.skin_joints[s].push_back(joint);
    }
  }
  if (sk.joint_node.size() > std::numeric_limits<std::uint16_t>::max())
    fail(ctx.file, "has " + std::to_string(sk.joint_node.size()) + " joints, more than 65535");
  return sk;
}

std::vector<int> joint_parents(const NodeGraph& graph, const SkeletonBuild& sk) {
  std::vector<int> parent(sk.joint_node.size(), -1);
  for (std::size_t j = 0; j < sk.joint_node.size(); ++j)
    for (int n = graph.parent[static_cast<std::size_t>(sk.joint_node[j])]; n >= 0;
         n = graph.parent[static_cast<std::size_t>(n)])
      if (sk.joint_of_node[static_cast<std::size_t>(n)] >= 0) {
        parent[j] = sk.joint_of_node[static_cast<std::size_t>(n)];
        break;
      }
  return parent;
}

// Mesh space -> world rest frame: R = G_root(rest) * B_root^-1. glTF skinned vertices live in
// "mesh space", which need not be +Y up or metres (CesiumMan's is Z-up; the scene's Z_UP node
// and the joint transforms carry the conversion). Storing R * p as the bind position and
// B_j^-1 * R^-1 as the inverse bind matrix leaves every skinned result unchanged
// (G_j B_j^-1 R^-1 R p = G_j B_j^-1 p) but puts the bind pose in the same world frame as the
// posed vertices, so bind-pose lengths (e.g. the pose-selection distance d) are in world units.
// Falls back to the identity if R is (nearly) singular.
Mat4d mesh_to_world(const Eigen::Affine3d& root_rest_global, const Mat4d& root_inverse_bind) {
  const Mat4d r = root_rest_global.matrix() * root_inverse_bind;
  if (!r.allFinite()) return Mat4d::Identity();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(r.topLeftCorner<3, 3>());
  const auto& sv = svd.singularValues();
  if (sv[0] <= 0 || sv[2] < 1e-6 * sv[0]) return Mat4d::Identity();
  Mat4d out = r;
  out.row(3) = Eigen::RowVector4d(0, 0, 0, 1);
  return out;
}

}  // namespace tourmap::crowd::gltf
