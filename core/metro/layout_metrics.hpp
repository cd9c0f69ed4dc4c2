#pragma once
// The comparison figures of ../shared/tools/metro_compare.py (one metric tool for tourmap and
// loom/octi alike), computed the same way on a layout in memory, so the benchmark can print
// them beside octi's. Definitions as in the tool's docstring:
//   - junctions (non-station nodes) of degree 2 are contracted into their edges, and each
//     edge's polyline is merged into pieces: consecutive segments while the direction stays
//     within 1 degree of the piece's start-to-end direction;
//   - bends: piece-to-piece turns of more than 1 degree inside the (contracted) edges, plus
//     stations of degree 2 where the last piece in and the first piece out differ by more than
//     1 degree (a reversal counts); lines through stations of degree >= 3 are not counted;
//   - displacement: least-squares similarity (scale, rotation, translation) of the layout's
//     stations onto their geographic positions; RMS residual / the diagonal of the stations'
//     geographic bounding box;
//   - min/mean edge: shortest contracted edge over the mean, by polyline length;
//   - octilinear share: pieces within 1 degree of a multiple of 45 degrees.
// The tool's round-corner and planarisation-node normalisations do not apply to tourmap
// layouts (octilinear bends, no added nodes) and are left out.

#include "metro/layout_graph.hpp"

#include <vector>

namespace tourmap::metro {

struct CompareMetrics {
  std::size_t bends = 0, interior_bends = 0, station_bends = 0;
  double displacement = 0;        // share of the geographic diagonal
  double min_over_mean_edge = 0;
  double octilinear_share = 0;    // of pieces
  std::size_t pieces = 0;
  std::size_t edges = 0;          // after contracting degree-2 junctions
  std::size_t edges_kept = 0;     // of those, drawn from their start node to their end node
};

// `g.pos`: geographic positions (metres); `is_station` per node; `layout` in any planar frame
// (every figure is invariant under a similarity).
CompareMetrics metro_compare_metrics(const LayoutGraph& g, const std::vector<bool>& is_station, const Layout& layout);

}  // namespace tourmap::metro
