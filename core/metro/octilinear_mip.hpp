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
// Like the paper, no planarity constraints: the result is checked for crossings and circular
// order afterwards and kept only when it is no worse than the start.

#include "metro/layout_graph.hpp"
#include "metro/mip_model.hpp"

namespace tourmap::metro {

struct MipLayoutParams {
  double w_bend = 1.0, w_topo = 50.0, w_length = 1.0;
  double l_const = 10.0;
};

struct OctilinearMip {
  MipModel model;
  std::vector<int> x, y;                       // columns per MIP node (originals first)
  std::vector<std::vector<std::uint32_t>> edge_nodes;  // per original edge: its MIP nodes in order
  double start_objective = 0;  // the start's value of the model's objective
};

OctilinearMip build_octilinear_mip(const LayoutGraph& g, const Layout& start, const MipLayoutParams& params);

// The layout a MIP solution describes (collinear dummy nodes dropped).
Layout decode_octilinear_mip(const OctilinearMip& mip, const std::vector<double>& solution, std::size_t nodes);

}  // namespace tourmap::metro
