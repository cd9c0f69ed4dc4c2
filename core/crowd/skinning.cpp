#include "crowd/skinning.hpp"

#include <stdexcept>
#include <string>

namespace tourmap::crowd {
namespace {

void check_pose(const SkinnedModel& model, const Pose& pose) {
  if (pose.skinning.size() != model.skeleton.parent.size())
    throw std::invalid_argument("skinning: the pose has " + std::to_string(pose.skinning.size()) +
                                " matrices, the skeleton " + std::to_string(model.skeleton.parent.size()) + " joints");
  const std::size_t n = model.positions.size();
  if (model.joints.size() != n || model.weights.size() != n)
    throw std::invalid_argument("skinning: joints/weights arrays do not match the vertex count");
}

void check_vertex(const SkinnedModel& model, std::size_t v, const Pose& pose) {
  if (v >= model.positions.size())
    throw std::out_of_range("skinning: vertex " + std::to_string(v) + " of " + std::to_string(model.positions.size()));
  for (std::size_t k = 0; k < 4; ++k)
    if (model.weights[v][k] != 0 && model.joints[v][k] >= pose.skinning.size())
      throw std::invalid_argument("skinning: vertex " + std::to_string(v) + " uses joint " +
                                  std::to_string(model.joints[v][k]) + " the pose does not have");
}

}  // namespace

Eigen::Matrix<float, 3, 4> blended_matrix(const SkinnedModel& model, std::size_t v, const Pose& pose) {
  Eigen::Matrix<float, 3, 4> m = Eigen::Matrix<float, 3, 4>::Zero();
  for (std::size_t k = 0; k < 4; ++k) {
    const float w = model.weights[v][k];
    if (w != 0) m += w * pose.skinning[model.joints[v][k]].matrix().topRows<3>();  // eq. 3.1
  }
  return m;
}

Vec3 skin_position(const SkinnedModel& model, std::size_t vertex, const Pose& pose) {
  check_pose(model, pose);
  check_vertex(model, vertex, pose);
  const Eigen::Matrix<float, 3, 4> m = blended_matrix(model, vertex, pose);
  return m.leftCols<3>() * model.positions[vertex] + m.col(3);
}

Vec3 skin_normal(const SkinnedModel& model, std::size_t vertex, const Pose& pose) {
  check_pose(model, pose);
  check_vertex(model, vertex, pose);
  if (model.normals.size() != model.positions.size())
    throw std::invalid_argument("skinning: normals array does not match the vertex count");
  const Vec3 n = blended_matrix(model, vertex, pose).leftCols<3>() * model.normals[vertex];
  const float len = n.norm();
  return len > 0 ? Vec3(n / len) : model.normals[vertex];
}

void skin_positions(const SkinnedModel& model, const Pose& pose, std::vector<Vec3>& out) {
  check_pose(model, pose);
  const std::size_t n = model.positions.size();
  for (std::size_t v = 0; v < n; ++v) check_vertex(model, v, pose);
  out.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    const Eigen::Matrix<float, 3, 4> m = blended_matrix(model, v, pose);
    out[v] = m.leftCols<3>() * model.positions[v] + m.col(3);
  }
}

void skin_normals(const SkinnedModel& model, const Pose& pose, std::vector<Vec3>& out) {
  check_pose(model, pose);
  const std::size_t n = model.positions.size();
  if (model.normals.size() != n) throw std::invalid_argument("skinning: normals array does not match the vertex count");
  for (std::size_t v = 0; v < n; ++v) check_vertex(model, v, pose);
  out.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    const Vec3 nv = blended_matrix(model, v, pose).leftCols<3>() * model.normals[v];
    const float len = nv.norm();
    out[v] = len > 0 ? Vec3(nv / len) : model.normals[v];
  }
}

}  // namespace tourmap::crowd
