#include "crowd/deformation_level.hpp"

#include "crowd/mesh_topology.hpp"
#include "crowd/skinning.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tourmap::crowd {
namespace {

int joint_depth(const Skeleton& s, int j) {
  int d = 0;
  for (int p = s.parent[static_cast<std::size_t>(j)]; p >= 0; p = s.parent[static_cast<std::size_t>(p)]) {
    if (p >= static_cast<int>(s.parent.size())) throw std::invalid_argument("skeleton: parent index out of range");
    if (++d > static_cast<int>(s.parent.size())) throw std::invalid_argument("skeleton: the parents form a cycle");
  }
  return d;
}

// Least common ancestor of two joints (-1 when they are in different trees).
int common_ancestor(const Skeleton& s, int a, int b) {
  int da = joint_depth(s, a), db = joint_depth(s, b);
  while (da > db) { a = s.parent[static_cast<std::size_t>(a)]; --da; }
  while (db > da) { b = s.parent[static_cast<std::size_t>(b)]; --db; }
  while (a != b && a >= 0 && b >= 0) {
    a = s.parent[static_cast<std::size_t>(a)];
    b = s.parent[static_cast<std::size_t>(b)];
  }
  return a == b ? a : -1;
}

// Skinned positions (eq. 3.1); a model without skin arrays stays in its bind pose.
void pose_positions(const SkinnedModel& m, const Pose& pose, std::vector<Vec3>& out) {
  if (m.weights.empty() || pose.skinning.empty())
    out = m.positions;
  else
    skin_positions(m, pose, out);
}

void require_pose_matches(const SkinnedModel& m, const Animation& a, std::size_t p) {
  const std::size_t nj = m.skeleton.parent.size();
  const Pose& pose = a.poses[p];
  const bool identity_static = nj <= 1 && pose.skinning.empty();
  if (!identity_static && (pose.skinning.size() != nj || pose.global.size() != nj))
    throw std::invalid_argument("model '" + m.name + "', animation '" + a.name + "', pose " + std::to_string(p) +
                                ": " + std::to_string(pose.skinning.size()) + " skinning and " +
                                std::to_string(pose.global.size()) + " global matrices for " +
                                std::to_string(nj) + " joints");
}

}  // namespace

int influence_ancestor(const Skeleton& s, const std::array<std::uint16_t, 4>& joints,
                       const std::array<float, 4>& weights) {
  int lca = -2;  // -2: no influence seen yet
  for (std::size_t k = 0; k < 4; ++k) {
    if (!(weights[k] > 0)) continue;
    const int j = joints[k];
    if (j >= static_cast<int>(s.parent.size())) return -1;
    lca = lca == -2 ? j : common_ancestor(s, lca, j);
    if (lca < 0) return -1;
  }
  return lca < 0 ? -1 : lca;
}

VertexTrajectories vertex_trajectories(const SkinnedModel& m) {
  require_consistent_mesh(m);
  const std::size_t nv = m.positions.size();
  const bool has_influences = !m.weights.empty();
  std::vector<int> frame(nv, -1);
  if (has_influences)
    for (std::size_t v = 0; v < nv; ++v) frame[v] = influence_ancestor(m.skeleton, m.joints[v], m.weights[v]);

  VertexTrajectories out;
  out.bounds.assign(nv, Box3());  // empty boxes
  std::vector<Box3> local(nv, Box3());  // trajectory in the frame of b_a
  std::vector<Affine> inverse_global;
  std::vector<Vec3> posed;
  bool any_pose = false;
  for (const Animation& a : m.animations) {
    for (std::size_t p = 0; p < a.poses.size(); ++p) {
      require_pose_matches(m, a, p);
      const Pose& pose = a.poses[p];
      // The bone frame with its scale divided out, so levels stay in model units whatever scale
      // the rig's nodes carry (glTF rigs are often in centimetres under a 0.01 root).
      inverse_global.resize(pose.global.size());
      for (std::size_t j = 0; j < pose.global.size(); ++j) {
        const float scale = std::cbrt(std::abs(pose.global[j].linear().determinant()));
        inverse_global[j] = pose.global[j].inverse(Eigen::Affine);
        if (scale > 0) inverse_global[j] = Eigen::Scaling(scale) * inverse_global[j];
      }
      pose_positions(m, pose, posed);
      for (std::size_t v = 0; v < nv; ++v) {
        const Vec3& x = posed[v];
        out.bounds[v].extend(x);
        const int b = frame[v];
        local[v].extend(b >= 0 && !inverse_global.empty() ? Vec3(inverse_global[static_cast<std::size_t>(b)] * x) : x);
      }
      any_pose = true;
    }
  }
  out.deformation_level.assign(nv, 0.f);
  if (!any_pose) {
    for (std::size_t v = 0; v < nv; ++v) out.bounds[v] = Box3(m.positions[v], m.positions[v]);
    return out;
  }
  for (std::size_t v = 0; v < nv; ++v) out.deformation_level[v] = local[v].diagonal().norm();
  return out;
}

std::vector<float> deformation_levels(const SkinnedModel& m) { return vertex_trajectories(m).deformation_level; }

}  // namespace tourmap::crowd
