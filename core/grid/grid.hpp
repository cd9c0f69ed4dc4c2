#pragma once
// Deformation grids (paper 4.4.1): a uniform NxN grid, or an adaptive grid refined as a
// restricted quadtree, over a square-celled frame around the map. Both share one structure:
// leaf quads with four corner vertices, T-junction vertices where a coarse quad meets finer
// ones, and each vertex's four orthogonal neighbours for Laplacian smoothing.
//
// Coordinates are planar (the map's local projection, normalised). Positions live on an integer
// lattice at the finest level, so vertices are shared exactly between quads.

#include "geo/projection.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace tourmap::grid {

using geo::XY;

struct Quad {
  std::array<std::uint32_t, 4> corners;  // counter-clockwise from (x0, y0): (x0,y0) (x1,y0) (x1,y1) (x0,y1)
  int level = 0;                         // 0 = base cell; each split adds 1
  XY min;                                // lower-left corner (original position)
  double size = 0.0;                     // side length (cells are square)
};

// A vertex on the midpoint of a coarse quad's side, shared by the two finer quads next to it
// but not a corner of the coarse quad.
struct TJunction {
  std::uint32_t vertex = 0;
  std::uint32_t coarse_quad = 0;
  int side = 0;  // 0 bottom, 1 right, 2 top, 3 left of the coarse quad
};

// One orthogonal neighbour of a vertex for smoothing: another vertex, or the centroid of a
// bigger quad (for a T-junction whose fourth direction runs into that quad), or none (boundary).
struct Neighbor {
  enum class Kind : std::uint8_t { none, vertex, quad_centroid };
  Kind kind = Kind::none;
  std::uint32_t index = 0;  // vertex or quad index
};

enum Direction { kLeft = 0, kRight = 1, kDown = 2, kUp = 3 };

struct Grid {
  XY origin;            // lower-left corner of the frame
  double cell = 0.0;    // base cell size
  int cols = 0, rows = 0;  // base cells
  int max_level = 0;    // deepest level present
  std::vector<XY> vertices;
  std::vector<bool> on_boundary;                 // on the frame's outline
  std::vector<std::array<Neighbor, 4>> neighbors;  // by Direction
  std::vector<Quad> quads;                       // leaves only
  std::vector<TJunction> tjunctions;

  // Quad containing `p` (clamped into the frame), via the finest-level lookup table.
  std::uint32_t quad_at(XY p) const;

  // Internal: leaf index per finest-level cell, row-major (cols * 2^max_level wide).
  std::vector<std::uint32_t> cell_quad;
};

struct AdaptiveParams {
  int base = 10;          // base cells along the frame's longer side
  int max_depth = 3;      // splits below the base level
  int max_vertices = 8;   // `c`: a quad holding more road vertices than this splits
};

// The square-celled frame around `points`: the bbox padded by `margin` (fraction of its size),
// grown so that `cells` cells span the longer side.
struct Frame {
  XY origin;
  double cell = 0.0;
  int cols = 0, rows = 0;
};
Frame frame_around(const std::vector<XY>& points, int cells_on_longer_side, double margin = 0.02);

// Finest-level cells of a frame refined to `depth`: what building the grid costs in memory
// (a few bytes per cell), so callers can refuse grids that are too fine before building them.
inline std::uint64_t lattice_cells(const Frame& frame, int depth) {
  return (static_cast<std::uint64_t>(frame.cols) << depth) * (static_cast<std::uint64_t>(frame.rows) << depth);
}

Grid build_uniform(const Frame& frame);
// Refines each base cell while it holds more than `max_vertices` of `points`, or any of
// `special` (guide vertices), up to `max_depth`; then balances to a restricted quadtree.
Grid build_adaptive(const Frame& frame, const std::vector<XY>& points, const std::vector<XY>& special,
                    const AdaptiveParams& params);

// Distinct grid edges: sides between consecutive vertices along quad outlines.
std::size_t count_grid_edges(const Grid& grid);

}  // namespace tourmap::grid
