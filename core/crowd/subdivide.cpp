#include "crowd/subdivide.hpp"

#include "crowd/mesh_normals.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace tourmap::crowd {
namespace {

// OpenMesh's LoopT subdivider moves only the points: it cannot carry skin weights or colours
// to the new vertices. So OpenMesh provides the connectivity (vertex rings, edge faces,
// boundary tests) and the Loop stencils are applied here, once, to every attribute.
using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

constexpr int kMaxLevels = 6;
constexpr std::size_t kMaxTriangles = std::size_t{1} << 26;

// A new vertex as a weighted sum of old vertices (weights are non-negative and sum to 1).
using Stencil = std::vector<std::pair<std::uint32_t, double>>;

// Loop's weight for each of the n ring neighbours of an interior vertex.
double loop_beta(std::size_t n) {
  const double c = 3.0 / 8.0 + 0.25 * std::cos(2 * std::numbers::pi / static_cast<double>(n));
  return (5.0 / 8.0 - c * c) / static_cast<double>(n);
}

Stencil even_stencil(const Mesh& mesh, Mesh::VertexHandle v) {
  const auto self = static_cast<std::uint32_t>(v.idx());
  if (mesh.is_isolated(v)) return {{self, 1.0}};
  if (mesh.is_boundary(v)) {
    // Crease rule: 3/4 self + 1/8 each of the two boundary neighbours. A vertex with more
    // boundary edges (a non-manifold pinch) stays where it is.
    Stencil s;
    for (const auto h : mesh.voh_range(v))
      if (mesh.is_boundary(mesh.edge_handle(h)))
        s.emplace_back(static_cast<std::uint32_t>(mesh.to_vertex_handle(h).idx()), 0.125);
    if (s.size() != 2) return {{self, 1.0}};
    s.emplace_back(self, 0.75);
    return s;
  }
  const std::size_t valence = mesh.valence(v);
  const double beta = loop_beta(valence);
  Stencil s;
  for (const auto w : mesh.vv_range(v)) s.emplace_back(static_cast<std::uint32_t>(w.idx()), beta);
  s.emplace_back(self, 1.0 - beta * static_cast<double>(valence));
  return s;
}

Stencil odd_stencil(const Mesh& mesh, Mesh::EdgeHandle e) {
  const auto h0 = mesh.halfedge_handle(e, 0);
  const auto a = static_cast<std::uint32_t>(mesh.to_vertex_handle(h0).idx());
  const auto b = static_cast<std::uint32_t>(mesh.from_vertex_handle(h0).idx());
  if (mesh.is_boundary(e)) return {{a, 0.5}, {b, 0.5}};
  const auto h1 = mesh.opposite_halfedge_handle(h0);
  const auto c = static_cast<std::uint32_t>(mesh.to_vertex_handle(mesh.next_halfedge_handle(h0)).idx());
  const auto d = static_cast<std::uint32_t>(mesh.to_vertex_handle(mesh.next_halfedge_handle(h1)).idx());
  return {{a, 0.375}, {b, 0.375}, {c, 0.125}, {d, 0.125}};
}

// Source model vertex of each mesh vertex (duplicates made for faces OpenMesh rejects point
// back at the vertex they copy).
struct Attributes {
  const SkinnedModel& model;
  const std::vector<std::uint32_t>& source;
};

void blend(const Attributes& in, const Stencil& s, SkinnedModel& out) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector4d color = Eigen::Vector4d::Zero();
  // Merge influences: same joint adds up; then the 4 largest are kept and renormalised.
  std::vector<std::pair<std::uint16_t, double>> influences;
  for (const auto& [v, w] : s) {
    const std::uint32_t src = in.source[v];
    p += w * in.model.positions[src].cast<double>();
    for (int c = 0; c < 4; ++c) color[c] += w * in.model.colors[src][static_cast<std::size_t>(c)];
    for (std::size_t k = 0; k < 4; ++k) {
      const float jw = in.model.weights[src][k];
      if (jw <= 0) continue;
      const std::uint16_t joint = in.model.joints[src][k];
      auto it = std::find_if(influences.begin(), influences.end(), [&](const auto& x) { return x.first == joint; });
      if (it == influences.end())
        influences.emplace_back(joint, w * jw);
      else
        it->second += w * jw;
    }
  }
  std::sort(influences.begin(), influences.end(), [](const auto& x, const auto& y) {
    return x.second != y.second ? x.second > y.second : x.first < y.first;
  });
  if (influences.size() > 4) influences.resize(4);
  double sum = 0;
  for (const auto& x : influences) sum += x.second;
  std::array<std::uint16_t, 4> joints{0, 0, 0, 0};
  std::array<float, 4> weights{0, 0, 0, 0};
  if (sum <= 0) {
    weights[0] = 1;  // only possible for a model without influences; keep it valid
  } else {
    for (std::size_t k = 0; k < influences.size(); ++k) {
      joints[k] = influences[k].first;
      weights[k] = static_cast<float>(influences[k].second / sum);
    }
  }
  out.positions.emplace_back(p.cast<float>());
  std::array<std::uint8_t, 4> c8{};
  for (int c = 0; c < 4; ++c)
    c8[static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(std::clamp(std::lround(color[c]), 0L, 255L));
  out.colors.push_back(c8);
  out.joints.push_back(joints);
  out.weights.push_back(weights);
}

SkinnedModel loop_once(const SkinnedModel& m) {
  const std::size_t n = m.positions.size();
  Mesh mesh;
  mesh.reserve(n, n * 3, m.triangle_count());
  std::vector<std::uint32_t> source(n);
  for (std::size_t v = 0; v < n; ++v) {
    source[v] = static_cast<std::uint32_t>(v);
    mesh.add_vertex(Mesh::Point(m.positions[v].x(), m.positions[v].y(), m.positions[v].z()));
  }
  // Faces in input order. OpenMesh refuses faces that would make a non-manifold edge; such a
  // face gets its own copies of its corners (what OpenMesh's file readers do as well).
  std::vector<std::array<Mesh::VertexHandle, 3>> corners;
  corners.reserve(m.triangle_count());
  const bool errors_on = omerr().is_enabled();
  omerr().disable();  // the rejected faces are expected and handled
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    std::array<Mesh::VertexHandle, 3> vh;
    for (std::size_t k = 0; k < 3; ++k) vh[k] = Mesh::VertexHandle(static_cast<int>(m.indices[3 * t + k]));
    if (vh[0] == vh[1] || vh[1] == vh[2] || vh[0] == vh[2]) {
      if (errors_on) omerr().enable();
      throw std::invalid_argument("subdivide: triangle " + std::to_string(t) + " repeats a vertex (weld first)");
    }
    if (!mesh.add_face(vh[0], vh[1], vh[2]).is_valid()) {
      for (auto& h : vh) {
        source.push_back(source[static_cast<std::size_t>(h.idx())]);
        const Mesh::Point corner = mesh.point(h);  // a copy: add_vertex may reallocate the points
        h = mesh.add_vertex(corner);
      }
      mesh.add_face(vh[0], vh[1], vh[2]);  // isolated corners: always accepted
    }
    corners.push_back(vh);
  }
  if (errors_on) omerr().enable();

  SkinnedModel out;
  out.name = m.name;
  out.skeleton = m.skeleton;
  out.animations = m.animations;
  const std::size_t nv = mesh.n_vertices(), ne = mesh.n_edges();
  out.positions.reserve(nv + ne);
  out.colors.reserve(nv + ne);
  out.joints.reserve(nv + ne);
  out.weights.reserve(nv + ne);
  const Attributes in{m, source};
  for (const auto v : mesh.vertices()) blend(in, even_stencil(mesh, v), out);  // indices 0..nv-1
  for (const auto e : mesh.edges()) blend(in, odd_stencil(mesh, e), out);      // nv + edge index

  out.indices.reserve(m.indices.size() * 4);
  auto edge_vertex = [&](Mesh::VertexHandle a, Mesh::VertexHandle b) {
    return static_cast<std::uint32_t>(nv + static_cast<std::size_t>(mesh.edge_handle(mesh.find_halfedge(a, b)).idx()));
  };
  for (const auto& [a, b, c] : corners) {
    const auto ia = static_cast<std::uint32_t>(a.idx()), ib = static_cast<std::uint32_t>(b.idx()),
               ic = static_cast<std::uint32_t>(c.idx());
    const std::uint32_t ab = edge_vertex(a, b), bc = edge_vertex(b, c), ca = edge_vertex(c, a);
    out.indices.insert(out.indices.end(), {ia, ab, ca, ib, bc, ab, ic, ca, bc, ab, bc, ca});
  }
  return out;
}

void check_model(const SkinnedModel& m) {
  const std::size_t n = m.positions.size();
  if (m.colors.size() != n || m.joints.size() != n || m.weights.size() != n)
    throw std::invalid_argument("subdivide: vertex attribute arrays differ in length");
  if (m.indices.size() % 3 != 0) throw std::invalid_argument("subdivide: index count is not a multiple of 3");
  for (std::uint32_t i : m.indices)
    if (i >= n) throw std::invalid_argument("subdivide: index " + std::to_string(i) + " out of range");
}

}  // namespace

SkinnedModel subdivide(const SkinnedModel& model, int levels) {
  if (levels < 0 || levels > kMaxLevels)
    throw std::invalid_argument("subdivide: levels must be in [0, " + std::to_string(kMaxLevels) + "], got " +
                                std::to_string(levels));
  check_model(model);
  if (model.triangle_count() > (kMaxTriangles >> (2 * levels)))
    throw std::invalid_argument("subdivide: " + std::to_string(levels) + " levels would exceed " +
                                std::to_string(kMaxTriangles) + " triangles");
  SkinnedModel out = model;
  for (int l = 0; l < levels; ++l) out = loop_once(out);
  if (levels > 0) {
    out.normals = smooth_normals(out.positions, out.indices);
    out.name = model.name + "_loop" + std::to_string(levels);
  }
  return out;
}

}  // namespace tourmap::crowd
