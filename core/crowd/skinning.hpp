#pragma once
// Linear blend skinning on the CPU (eq. 3.1): v' = sum_k w_k M_{j_k} v with the pose's skinning
// matrices M_j = G_j * B_j^-1. Normals use the blended linear part (no translation) and are
// renormalised; that is exact for rigid and uniformly scaled joints, which is what skeletons use.

#include "crowd/skinned_model.hpp"

#include <cstddef>
#include <vector>

namespace tourmap::crowd {

// Throws std::out_of_range for a bad vertex, std::invalid_argument if the pose does not have
// one matrix per joint or a vertex references a joint the pose lacks.
Vec3 skin_position(const SkinnedModel& model, std::size_t vertex, const Pose& pose);
Vec3 skin_normal(const SkinnedModel& model, std::size_t vertex, const Pose& pose);

// Every vertex; `out` is resized to the vertex count.
void skin_positions(const SkinnedModel& model, const Pose& pose, std::vector<Vec3>& out);
void skin_normals(const SkinnedModel& model, const Pose& pose, std::vector<Vec3>& out);

// The blended skinning matrix of one vertex, sum_k w_k M_{j_k} (no checks; callers validate).
Eigen::Matrix<float, 3, 4> blended_matrix(const SkinnedModel& model, std::size_t vertex, const Pose& pose);

}  // namespace tourmap::crowd
