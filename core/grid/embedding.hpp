#pragma once
// Points embedded in grid quads by bilinear coordinates (paper eq. 4.2): a road vertex is the
// bilinear combination of its quad's four corners, so it follows the quad when the grid deforms.

#include "grid/grid.hpp"

#include <array>
#include <optional>

namespace tourmap::grid {

struct Embedding {
  std::uint32_t quad = 0;
  std::array<double, 4> weight{};  // of the quad's corners, in Quad::corners order; sums to 1
};

// p(u, v) on the quad with corners c0..c3 (counter-clockwise from the (0,0) corner).
XY bilinear(const std::array<XY, 4>& corners, double u, double v);
// The (u, v) with bilinear(corners, u, v) == p for a convex quad, or nullopt when p is outside
// it (beyond `tolerance` in parameter space).
std::optional<std::array<double, 2>> inverse_bilinear(const std::array<XY, 4>& corners, XY p,
                                                      double tolerance = 1e-9);

// Embeds a point in the original grid (the quad under it, by the lookup table).
Embedding embed(const Grid& grid, XY p);
// Where an embedded point is on a grid with vertex positions `positions`.
XY place(const Grid& grid, const std::vector<XY>& positions, const Embedding& e);
std::array<XY, 4> corners_of(const Grid& grid, const std::vector<XY>& positions, std::uint32_t quad);

}  // namespace tourmap::grid
