#pragma once
// Removing the road crossings a deformation adds (beyond paper 4.4.2, which only detects them).
//
// With no quad folded and the T-junctions on their coarse sides (foldover.hpp), the grid's map
// is one-to-one, so the true images of two roads never cross. What is drawn, though, is the
// straight chord between two deformed nodes, and where a quad is twisted (a bilinear map that is
// not affine) or an edge runs through quads that moved differently, the chord leaves the image
// and can cut across a neighbouring road. So: each edge carries sample points embedded at rest
// between its nodes and its clearance (the rest distance to the nearest other road). Two roads
// d apart at rest stay about sigma * d apart (sigma: the grid's least stretch around them), so
// only an edge whose chord strays from its samples by a good share of sigma * clearance is a
// suspect; suspects are tested against the chords around them (CGAL box intersection + exact
// segment predicates), and a pair that crosses now but neither crossed nor touched at rest (foldover.hpp)
// makes the quads under both edges smoother (their vertices' displacements halfway to their
// neighbours' average; rings around them join every few steps), until no such pair is left or
// the step cap is hit. The suspect filter is a bound, not a proof: count_added_crossings
// (foldover.hpp) is the exact count the API reports and the tests check. Costs residue only
// where it acts.

#include "deform/system.hpp"

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tourmap::deform {

// Interior sample points of every road edge, embedded in the rest grid: at least the midpoint,
// and enough that no two consecutive points are more than half the smaller end quad apart (16 at
// most). prepare_grid keeps them in Prepared::edge_samples.
EdgeSamples sample_edges(const grid::Grid& grid, const PlanarNetwork& net);

struct UntangleReport {
  int steps = 0;              // smoothing steps run
  std::size_t suspects = 0;   // edges whose chord left their image, at the first check
  std::size_t left = 0;       // new crossing pairs still there at the end (0 unless capped)
};

// Smooths `points` (grid vertices) until the chords of the road edges cross no pair that did not
// cross at rest, or `max_steps` is hit, or the clock reaches `until`; `nodes` is updated to the deformed road nodes.
UntangleReport untangle_crossings(const Prepared& p, const PlanarNetwork& net, std::vector<XY>& points, std::vector<XY>& nodes, int max_steps,
                                  std::chrono::steady_clock::time_point until = std::chrono::steady_clock::time_point::max());

}  // namespace tourmap::deform
