#pragma once
// Vertex welding: glTF exporters split vertices along UV and normal seams; clustering needs
// triangle adjacency across those seams and the simplifier needs a connected surface, so
// vertices at bitwise-equal positions are merged. By default only vertices that also have the
// same skin influences are merged: they move identically in every pose, so the weld can never
// change an animated surface (two rigid parts that merely touch at a vertex stay apart).

#include "crowd/skinned_model.hpp"

#include <cstddef>

namespace tourmap::crowd {

struct WeldStats {
  std::size_t vertices_before = 0;
  std::size_t vertices_after = 0;
  std::size_t degenerate_triangles_removed = 0;  // two corners became one vertex
  std::size_t unreferenced_vertices_removed = 0;
};

// Merges vertices in place (colours of merged vertices are averaged; normals are kept from the
// first and should be recomputed), drops triangles that became degenerate, and compacts away
// vertices no triangle uses. Vertex order is kept (first occurrence).
WeldStats weld_vertices(SkinnedModel& model, bool require_equal_skinning = true);

}  // namespace tourmap::crowd
