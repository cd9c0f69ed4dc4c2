#pragma once
// Smooth vertex normals: the area-weighted sum of the incident triangles' normals, normalised.

#include "crowd/skinned_model.hpp"

#include <vector>

namespace tourmap::crowd {

// One normal per position; a vertex in no (non-degenerate) triangle gets +Y.
std::vector<Vec3> smooth_normals(const std::vector<Vec3>& positions, const std::vector<std::uint32_t>& indices);

}  // namespace tourmap::crowd
