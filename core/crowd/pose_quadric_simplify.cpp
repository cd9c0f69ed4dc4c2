#include "crowd/pose_quadric_simplify.hpp"

#include "crowd/skinning.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

// OpenMesh's Decimater fits the multi-pose metric: it owns the priority queue, the half-edge
// collapse, the link-condition/border legality tests and vertex locking, and a custom module
// (ModBaseT) supplies the cost (max over poses) and the multi-pose flip test. The module reads
// per-pose positions and quadrics from flat arrays indexed by vertex id, so nothing is allocated
// per collapse.

namespace tourmap::crowd {
namespace {

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
constexpr std::size_t quadric_size = 10;  // upper triangle of a symmetric 4x4

// Adds the plane n.x + d = 0 (unit n) to a quadric.
void add_plane(double* q, const Eigen::Vector3d& n, double d) {
  const double a = n.x(), b = n.y(), c = n.z();
  q[0] += a * a; q[1] += a * b; q[2] += a * c; q[3] += a * d;
  q[4] += b * b; q[5] += b * c; q[6] += b * d;
  q[7] += c * c; q[8] += c * d;
  q[9] += d * d;
}

// Sum of squared distances of x to the planes of q.
double evaluate(const double* q, const Vec3& xf) {
  const double x = xf.x(), y = xf.y(), z = xf.z();
  return q[0] * x * x + 2 * q[1] * x * y + 2 * q[2] * x * z + 2 * q[3] * x + q[4] * y * y + 2 * q[5] * y * z +
         2 * q[6] * y + q[7] * z * z + 2 * q[8] * z + q[9];
}

// Skinned positions (eq. 3.1); a model without skin arrays stays in its bind pose.
void pose_positions(const SkinnedModel& m, const Pose& pose, std::vector<Vec3>& out) {
  if (m.weights.empty() || pose.skinning.empty())
    out = m.positions;
  else
    skin_positions(m, pose, out);
}

struct ClusterContext {
  const Vec3* positions = nullptr;  // [v * poses + p]
  double* quadrics = nullptr;       // [(v * poses + p) * 10]
  std::size_t poses = 0;
  OpenMesh::VPropHandleT<std::uint32_t> id;  // mesh vertex -> canonical vertex id
  double max_cost = 0;
};

// Decimater module: pose-aware quadric cost (max over representative poses) plus the rule that
// no remaining triangle may flip or degenerate in any representative pose.
template <class MeshT>
class ModPoseQuadricT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModPoseQuadricT, MeshT, PoseQuadric);

  explicit ModPoseQuadricT(MeshT& mesh) : Base(mesh, false) {}
  void set_context(ClusterContext* context) { ctx_ = context; }

  float collapse_priority(const CollapseInfo& ci) override {
    const MeshT& mesh = Base::mesh();
    const std::uint32_t removed = mesh.property(ctx_->id, ci.v0);
    const std::uint32_t kept = mesh.property(ctx_->id, ci.v1);
    for (auto f : mesh.vf_range(ci.v0)) {
      if (f == ci.fl || f == ci.fr) continue;  // these two disappear
      std::array<std::uint32_t, 3> corner{};
      int k = 0;
      for (auto v : mesh.fv_range(f)) corner[static_cast<std::size_t>(k++)] = mesh.property(ctx_->id, v);
      for (std::size_t p = 0; p < ctx_->poses; ++p) {
        const Vec3 a = at(corner[0], p), b = at(corner[1], p), c = at(corner[2], p);
        const Vec3 before = (b - a).cross(c - a);
        const Vec3 a2 = corner[0] == removed ? at(kept, p) : a;
        const Vec3 b2 = corner[1] == removed ? at(kept, p) : b;
        const Vec3 c2 = corner[2] == removed ? at(kept, p) : c;
        const Vec3 after = (b2 - a2).cross(c2 - a2);
        if (before.squaredNorm() > 0 && before.dot(after) <= 0) return float(Base::ILLEGAL_COLLAPSE);
      }
    }
    return static_cast<float>(cost(removed, kept));
  }

  void preprocess_collapse(const CollapseInfo& ci) override {
    const MeshT& mesh = Base::mesh();
    const std::uint32_t removed = mesh.property(ctx_->id, ci.v0);
    const std::uint32_t kept = mesh.property(ctx_->id, ci.v1);
    ctx_->max_cost = std::max(ctx_->max_cost, cost(removed, kept));
    for (std::size_t p = 0; p < ctx_->poses; ++p) {
      const double* from = quadric(removed, p);
      double* to = quadric(kept, p);
      for (std::size_t k = 0; k < quadric_size; ++k) to[k] += from[k];
    }
  }

 private:
  const Vec3& at(std::uint32_t v, std::size_t p) const { return ctx_->positions[v * ctx_->poses + p]; }
  double* quadric(std::uint32_t v, std::size_t p) const { return ctx_->quadrics + (v * ctx_->poses + p) * quadric_size; }

  // max over poses of (Q_removed^p + Q_kept^p)(x_kept^p); the error radius uses the max.
  double cost(std::uint32_t removed, std::uint32_t kept) const {
    double worst = 0;
    for (std::size_t p = 0; p < ctx_->poses; ++p) {
      const Vec3& x = at(kept, p);
      worst = std::max(worst, evaluate(quadric(removed, p), x) + evaluate(quadric(kept, p), x));
    }
    return worst;
  }

  ClusterContext* ctx_ = nullptr;
};

using ModPoseQuadric = ModPoseQuadricT<Mesh>;

}  // namespace

PoseQuadricSimplifier::PoseQuadricSimplifier(const SkinnedModel& m, std::vector<std::uint32_t> canonical,
                                             const std::vector<const Pose*>& poses)
    : canonical_(std::move(canonical)), poses_(poses.size()) {
  if (poses.empty()) throw std::invalid_argument("PoseQuadricSimplifier: no representative pose");
  if (canonical_.size() != m.vertex_count())
    throw std::invalid_argument("PoseQuadricSimplifier: canonical map does not match the vertex count");
  const std::size_t nv = m.vertex_count(), P = poses_;
  positions_.resize(nv * P);
  quadrics_.assign(nv * P * quadric_size, 0.0);
  local_of_.assign(nv, -1);

  // Open border edges of the welded base mesh: edges used by exactly one triangle.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edge_triangle;  // (edge key, triangle)
  const std::size_t nt = m.triangle_count();
  edge_triangle.reserve(3 * nt);
  auto corner = [&](std::size_t t, std::size_t k) { return canonical_[m.indices[3 * t + k]]; };
  for (std::size_t t = 0; t < nt; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint64_t a = corner(t, k), b = corner(t, (k + 1) % 3);
      if (a == b) continue;
      edge_triangle.emplace_back(std::min(a, b) << 32 | std::max(a, b), static_cast<std::uint32_t>(t));
    }
  std::sort(edge_triangle.begin(), edge_triangle.end());
  std::vector<std::pair<std::uint64_t, std::uint32_t>> border;
  for (std::size_t i = 0; i < edge_triangle.size();) {
    std::size_t j = i + 1;
    while (j < edge_triangle.size() && edge_triangle[j].first == edge_triangle[i].first) ++j;
    if (j == i + 1) border.push_back(edge_triangle[i]);
    i = j;
  }

  std::vector<Vec3> skinned;
  for (std::size_t p = 0; p < P; ++p) {
    pose_positions(m, *poses[p], skinned);
    for (std::size_t v = 0; v < nv; ++v) positions_[v * P + p] = skinned[canonical_[v]];
    auto pos = [&](std::uint32_t v) { return skinned[v].cast<double>(); };
    for (std::size_t t = 0; t < nt; ++t) {
      const std::uint32_t a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
      if (a == b || b == c || a == c) continue;
      Eigen::Vector3d n = (pos(b) - pos(a)).cross(pos(c) - pos(a));
      if (!(n.norm() > 0)) continue;  // degenerate in this pose: no plane
      n.normalize();
      const double d = -n.dot(pos(a));
      for (std::uint32_t v : {a, b, c}) add_plane(&quadrics_[(v * P + p) * quadric_size], n, d);
    }
    for (const auto& [key, t] : border) {
      const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key & 0xffffffffu);
      const Eigen::Vector3d face_n =
          (pos(corner(t, 1)) - pos(corner(t, 0))).cross(pos(corner(t, 2)) - pos(corner(t, 0)));
      Eigen::Vector3d n = (pos(b) - pos(a)).cross(face_n);
      if (!(n.norm() > 0)) continue;
      n.normalize();
      const double d = -n.dot(pos(a));
      for (std::uint32_t v : {a, b}) add_plane(&quadrics_[(v * P + p) * quadric_size], n, d);
    }
  }
}

SimplifyResult PoseQuadricSimplifier::simplify(const std::vector<std::uint32_t>& indices,
                                               std::size_t target_triangles,
                                               const std::function<bool(std::uint32_t)>& locked) {
  if (indices.size() % 3 != 0) throw std::invalid_argument("simplify: index count is not a multiple of 3");
  for (std::uint32_t v : indices)
    if (v >= canonical_.size())
      throw std::invalid_argument("simplify: vertex " + std::to_string(v) + " out of range (" +
                                  std::to_string(canonical_.size()) + " vertices)");
  const std::size_t nt = indices.size() / 3;
  SimplifyResult result;
  if (nt <= target_triangles) {
    result.indices = indices;
    result.reached_target = true;
    return result;
  }

  Mesh mesh;
  mesh.request_vertex_status();
  mesh.request_edge_status();
  mesh.request_halfedge_status();
  mesh.request_face_status();
  ClusterContext ctx;
  ctx.positions = positions_.data();
  ctx.quadrics = quadrics_.data();
  ctx.poses = poses_;
  mesh.add_property(ctx.id);
  OpenMesh::FPropHandleT<std::uint32_t> corners_of;  // face -> its entry in face_corners
  mesh.add_property(corners_of);

  std::vector<std::uint32_t> touched;  // canonical ids with a mesh vertex (local_of_ reset at the end)
  std::vector<Mesh::VertexHandle> handle;
  auto vertex_of = [&](std::uint32_t original) {
    const std::uint32_t c = canonical_[original];
    if (local_of_[c] < 0) {
      const Vec3& x = positions_[c * poses_];
      const Mesh::VertexHandle vh = mesh.add_vertex(Mesh::Point(x.x(), x.y(), x.z()));
      mesh.property(ctx.id, vh) = c;
      local_of_[c] = static_cast<int>(handle.size());
      handle.push_back(vh);
      touched.push_back(c);
    }
    return handle[static_cast<std::size_t>(local_of_[c])];
  };

  // OpenMesh reports rejected (non-manifold) faces on omerr; they are expected here and handled.
  const bool errors_were_on = omerr().is_enabled();
  omerr().disable();
  std::vector<std::array<std::uint32_t, 3>> face_corners;  // original ids, by face index
  std::vector<std::uint32_t> kept_as_is;
  for (std::size_t t = 0; t < nt; ++t) {
    const std::array<std::uint32_t, 3> o{indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]};
    const Mesh::VertexHandle a = vertex_of(o[0]), b = vertex_of(o[1]), c = vertex_of(o[2]);
    Mesh::FaceHandle f;
    if (a != b && b != c && a != c) f = mesh.add_face(a, b, c);
    if (f.is_valid()) {
      mesh.property(corners_of, f) = static_cast<std::uint32_t>(face_corners.size());
      face_corners.push_back(o);
    } else {
      kept_as_is.insert(kept_as_is.end(), o.begin(), o.end());
    }
  }
  if (errors_were_on) omerr().enable();

  for (std::size_t i = 0; i < handle.size(); ++i)
    if (locked(touched[i])) mesh.status(handle[i]).set_locked(true);
  for (std::uint32_t o : kept_as_is) mesh.status(handle[static_cast<std::size_t>(local_of_[canonical_[o]])]).set_locked(true);

  const std::size_t as_is = kept_as_is.size() / 3;
  const std::size_t mesh_target = target_triangles > as_is ? target_triangles - as_is : 0;
  {
    OpenMesh::Decimater::DecimaterT<Mesh> decimater(mesh);
    ModPoseQuadric::Handle module;
    decimater.add(module);
    decimater.module(module).set_context(&ctx);
    decimater.initialize();
    result.collapses = decimater.decimate_to_faces(0, mesh_target);
  }
  result.max_quadric_error = ctx.max_cost;

  result.indices = std::move(kept_as_is);
  for (const Mesh::FaceHandle f : mesh.faces()) {
    if (mesh.status(f).deleted()) continue;
    const auto& original = face_corners[mesh.property(corners_of, f)];
    for (const Mesh::VertexHandle v : mesh.fv_range(f)) {
      const std::uint32_t c = mesh.property(ctx.id, v);
      std::uint32_t out = c;
      for (std::uint32_t o : original)
        if (canonical_[o] == c) out = o;
      result.indices.push_back(out);
    }
  }
  result.reached_target = result.indices.size() / 3 <= target_triangles;
  for (std::uint32_t c : touched) local_of_[c] = -1;
  return result;
}

}  // namespace tourmap::crowd
