#include "crowd/gltf_primitive.hpp"

#include "crowd/gltf_material.hpp"
#include "load/load_error.hpp"

#include <Eigen/LU>

namespace tourmap::crowd::gltf {
namespace {

constexpr std::size_t kMaxVertices = std::size_t{1} << 28;

[[noreturn]] void fail(const std::string& file, const std::string& problem) { throw load::LoadError(file, problem); }

bool is_triangles(const tinygltf::Primitive& p) { return p.mode == TINYGLTF_MODE_TRIANGLES || p.mode == -1; }

}  // namespace

void append_primitive(const ReadContext& ctx, const tinygltf::Primitive& prim, const std::string& what,
                      const Binding& bind, MergedMesh& out) {
  const auto pos_it = prim.attributes.find("POSITION");
  if (!is_triangles(prim) || pos_it == prim.attributes.end()) {
    ++out.skipped_primitives;
    return;
  }
  const FloatAccessor pos = read_floats(ctx, pos_it->second, what + " POSITION", {3});
  const std::size_t n = pos.count;
  if (out.positions.size() + n > kMaxVertices)
    fail(ctx.file, "more than " + std::to_string(kMaxVertices) + " vertices");
  auto same_count = [&](const FloatAccessor& a, const char* name) {
    if (a.count != n)
      fail(ctx.file,
           what + " " + name + " has " + std::to_string(a.count) + " elements, POSITION " + std::to_string(n));
  };

  // Indices (validated against this primitive's vertex count) or the implied 0..n-1.
  std::vector<std::uint32_t> local;
  if (prim.indices >= 0) {
    local = read_uints(ctx, prim.indices, what + " indices", {1}).values;
    for (std::size_t i = 0; i < local.size(); ++i)
      if (local[i] >= n)
        fail(ctx.file, what + " index " + std::to_string(i) + " is " + std::to_string(local[i]) +
                           ", but there are only " + std::to_string(n) + " vertices");
  } else {
    local.resize(n);
    for (std::size_t i = 0; i < n; ++i) local[i] = static_cast<std::uint32_t>(i);
  }
  if (local.size() % 3 != 0)
    fail(ctx.file, what + " index count " + std::to_string(local.size()) + " is not a multiple of 3");

  const std::size_t base = out.positions.size();
  const Eigen::Affine3d to_bind(bind.to_bind);
  const Eigen::Matrix3d normal_matrix = bind.to_bind.topLeftCorner<3, 3>().inverse().transpose();
  for (std::size_t v = 0; v < n; ++v) {
    const Eigen::Vector3d p(pos.at(v, 0), pos.at(v, 1), pos.at(v, 2));
    out.positions.push_back((to_bind * p).cast<float>());
  }

  FloatAccessor normals;
  if (const auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
    normals = read_floats(ctx, it->second, what + " NORMAL", {3});
    same_count(normals, "NORMAL");
  }
  for (std::size_t v = 0; v < n; ++v) {
    Eigen::Vector3d nv = Eigen::Vector3d::Zero();
    if (normals.count) nv = normal_matrix * Eigen::Vector3d(normals.at(v, 0), normals.at(v, 1), normals.at(v, 2));
    const double len = nv.norm();
    out.has_normal.push_back(len > 1e-12 ? 1 : 0);
    out.normals.push_back(len > 1e-12 ? Vec3((nv / len).cast<float>()) : Vec3::UnitY());
  }

  const auto colors = primitive_colors(ctx, prim, n, what);
  out.colors.insert(out.colors.end(), colors.begin(), colors.end());

  if (bind.skin_joints) {
    const auto j_it = prim.attributes.find("JOINTS_0");
    const auto w_it = prim.attributes.find("WEIGHTS_0");
    const UintAccessor joints = read_uints(ctx, j_it->second, what + " JOINTS_0", {4});
    const FloatAccessor weights = read_floats(ctx, w_it->second, what + " WEIGHTS_0", {4});
    if (joints.count != n) fail(ctx.file, what + " JOINTS_0 count differs from POSITION");
    same_count(weights, "WEIGHTS_0");
    const std::vector<int>& map = *bind.skin_joints;
    for (std::size_t v = 0; v < n; ++v) {
      std::array<std::uint16_t, 4> j{0, 0, 0, 0};
      std::array<float, 4> w{0, 0, 0, 0};
      float sum = 0;
      for (int s = 0; s < 4; ++s) {
        float wv = weights.at(v, s);
        if (wv < -1e-3f) fail(ctx.file, what + " vertex " + std::to_string(v) + " has a negative skin weight");
        if (wv <= 0) continue;  // an unused slot: its joint index is irrelevant and left 0
        const std::uint32_t lj = joints.at(v, s);
        if (lj >= map.size())
          fail(ctx.file, what + " vertex " + std::to_string(v) + " uses joint " + std::to_string(lj) +
                             ", but the skin has " + std::to_string(map.size()) + " joints");
        j[static_cast<std::size_t>(s)] = static_cast<std::uint16_t>(map[lj]);
        w[static_cast<std::size_t>(s)] = wv;
        sum += wv;
      }
      if (sum <= 1e-6f) {
        // All-zero weights (seen in sloppy exports): bind rigidly to the vertex's first joint.
        const std::uint32_t lj = joints.at(v, 0);
        j = {static_cast<std::uint16_t>(lj < map.size() ? map[lj] : map[0]), 0, 0, 0};
        w = {1, 0, 0, 0};
      } else {
        for (float& x : w) x /= sum;  // glTF wants sum 1; renormalise small drifts
      }
      out.joints.push_back(j);
      out.weights.push_back(w);
    }
  } else {
    out.joints.insert(out.joints.end(), n, {static_cast<std::uint16_t>(bind.rigid_joint), 0, 0, 0});
    out.weights.insert(out.weights.end(), n, {1.f, 0.f, 0.f, 0.f});
  }
  for (std::uint32_t i : local) out.indices.push_back(static_cast<std::uint32_t>(base + i));
}

bool has_skin_attributes(const tinygltf::Primitive& p) {
  return p.attributes.count("JOINTS_0") && p.attributes.count("WEIGHTS_0");
}

// Turns the merged arrays into the model's vertex data: weld, normals.

}  // namespace tourmap::crowd::gltf
