#include "crowd/mesh_normals.hpp"

#include <stdexcept>

namespace tourmap::crowd {

std::vector<Vec3> smooth_normals(const std::vector<Vec3>& positions, const std::vector<std::uint32_t>& indices) {
  if (indices.size() % 3 != 0) throw std::invalid_argument("smooth_normals: index count is not a multiple of 3");
  std::vector<Eigen::Vector3d> sum(positions.size(), Eigen::Vector3d::Zero());
  for (std::size_t t = 0; t < indices.size(); t += 3) {
    const std::uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    if (a >= positions.size() || b >= positions.size() || c >= positions.size())
      throw std::invalid_argument("smooth_normals: index out of range");
    const Eigen::Vector3d pa = positions[a].cast<double>();
    // The cross product's length is twice the area: area weighting for free.
    const Eigen::Vector3d n = (positions[b].cast<double>() - pa).cross(positions[c].cast<double>() - pa);
    sum[a] += n;
    sum[b] += n;
    sum[c] += n;
  }
  std::vector<Vec3> out(positions.size());
  for (std::size_t v = 0; v < sum.size(); ++v) {
    const double len = sum[v].norm();
    out[v] = len > 0 ? Vec3((sum[v] / len).cast<float>()) : Vec3::UnitY();
  }
  return out;
}

}  // namespace tourmap::crowd
