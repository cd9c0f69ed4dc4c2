#pragma once
// The octilinear layout as a mixed-integer program (paper 5.4.2, after Nöllenburg and Wolff),
// started from a fast-path layout: every segment of the start layout becomes a MIP edge
// (bend points become degree-2 dummy nodes), so the start is a feasible solution that CBC can
// only improve.
//   - each MIP edge takes one of the octilinear directions closest to its start direction (the
//     start's sector and its two neighbours) or its edge's geographic sector, by binary choice;
//     eq. 5.3 for that direction: the offset perpendicular to it is 0 and the length along it is
//     at least the edge's share of l_uv (eq. 5.4);
//   - cost_bend: the turn (0..3 times 45 degrees) between consecutive segments of a line, at
//     dummy nodes and where a line passes a station;
//   - cost_topo (rpos): 1 when a segment leaves its edge's geographic sector;
//   - cost_length: the segment's L-infinity length in units of l_const;
//   - weights 1 / 50 / 1 (the paper's).
//   - degree-2 stations the start passes straight through are contracted: not MIP nodes, but
//     kept at their share of the one segment through them;
//   - circular order at every node (N&W's cyclic constraints), where the start keeps it;
//   - planarity (N&W's 8-direction separation) for segment pairs within 2 l_const of each other
//     in the start, offering only the directions that separate them there (all pairs would be
//     quadratic in size).
// Far pairs are unconstrained, so the result is checked for crossings and circular order
// afterwards and kept only when it is no worse than the start.

#include "metro/layout_graph.hpp"
#include "metro/mip_model.hpp"

namespace tourmap::metro {

struct MipLayoutParams {
  double w_bend = 1.0, w_topo = 50.0, w_length = 1.0;
  double w_place = 0.0;  // per l_const a station moves from the start, in x and in y (0: off)
  double l_const = 10.0;
};

// A contracted station: at fraction t of the MIP segment from node a to node b.
struct MipPlacement {
  bool on = false;
  std::uint32_t a = 0, b = 0;
  double t = 0;
};

struct OctilinearMip {
  MipModel model;
  std::vector<int> x, y;                       // columns per MIP node (originals first), -1 when contracted
  std::vector<MipPlacement> placement;         // per original node: where a contracted one stays
  std::vector<std::vector<std::uint32_t>> edge_nodes;  // per original edge: its MIP nodes in order
  double start_objective = 0;  // the start's value of the model's objective
};

OctilinearMip build_octilinear_mip(const LayoutGraph& g, const Layout& start, const MipLayoutParams& params);

// The layout a MIP solution describes (collinear dummy nodes dropped).
Layout decode_octilinear_mip(const OctilinearMip& mip, const std::vector<double>& solution, std::size_t nodes);

}  // namespace tourmap::metro
