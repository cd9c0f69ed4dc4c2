#pragma once
// Active clusters for a map window (paper 5.4.4, runtime): walking the cluster tree top-down, a
// cluster is active when its bbox lies inside the window and its bbox's larger side is smaller
// than the window's smaller side; the walk stops there. The active clusters are ranked by
// prominence p(c) = vw(c) / sum of vw over the active clusters; the top M are shown with their
// representative POI, the next M as previews.
//
// Extension (not in the paper): a window about the size of the whole map makes the root the only
// active cluster, which shows one POI. With `at_least` > 0 the active set is refined afterwards:
// while it has fewer than `at_least` clusters, the one with the largest bbox side that has
// children is replaced by them. Children of an active cluster lie inside the window, so the
// refined set still covers exactly the POIs the paper's set covers.

#include "geo/projection.hpp"
#include "poi/cluster_tree.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tourmap::poi {

struct ActiveClusters {
  std::vector<std::uint32_t> top, previews;  // node indices, by prominence descending (ties: lower index)
  std::vector<double> prominence;            // p(c) for top then previews, same order; 1/active each when all vw are 0
  std::size_t active = 0;                    // active clusters in the window
};

ActiveClusters active_clusters(const ClusterTree& tree, geo::XY window_min, geo::XY window_max, std::size_t m = 10,
                               std::size_t at_least = 0);

// The activity test on one node, for callers and tests.
bool is_active(const ClusterNode& node, geo::XY window_min, geo::XY window_max);

}  // namespace tourmap::poi
