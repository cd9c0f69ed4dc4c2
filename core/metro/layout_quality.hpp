#pragma once
// The quality report returned with every layout (and printed by the benchmark).

#include "metro/layout_graph.hpp"

namespace tourmap::metro {

struct LayoutQuality {
  double octilinear_share = 0;       // edges whose every segment is at a multiple of 45 degrees
  std::size_t bends = 0;             // direction changes inside edges and along lines at stations
  std::size_t crossings = 0;         // pairs of edges that cross in the layout
  std::size_t geo_crossings = 0;     // pairs of edges that cross geographically (straight lines)
  std::size_t added_crossings = 0;   // pairs that cross in the layout but not geographically
  std::size_t order_violations = 0;  // stations whose circular order of edges changed
  double min_edge = 0, mean_edge = 0;  // path lengths, layout units
  double mean_displacement = 0;      // mean station offset from the Helmert-aligned geography,
                                     // in mean edge lengths
  double min_station_gap = 0;        // smallest node-node (not joined by an edge) or node-path (of
                                     // an edge not ending there) distance, layout units
                                     // (metro/station_gap.hpp); +infinity without such a pair
  double min_station_gap_ratio = 0;  // min_station_gap / mean_edge
};

LayoutQuality measure_layout(const LayoutGraph& g, const Layout& layout);

// Stations (of degree >= 3) whose edges leave in another circular order than geographically,
// or two of them in the same direction.
std::size_t count_order_violations(const LayoutGraph& g, const Layout& layout);

// Pairs of polylines (one per edge) that intersect anywhere but at a shared end node: the
// pairs (i < j, sorted), and their count.
std::vector<std::pair<std::size_t, std::size_t>> crossing_path_pairs(
    const std::vector<std::vector<XY>>& paths, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges);
std::size_t count_path_crossings(const std::vector<std::vector<XY>>& paths,
                                 const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges);

}  // namespace tourmap::metro
