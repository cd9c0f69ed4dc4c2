#pragma once
// Incremental updates of a cluster tree (poi/cluster_tree.hpp): POIs added, removed, moved or
// re-weighted without rebuilding the hierarchy. Beyond the paper, which builds once.
//
// The tree changes locally:
//  - a removed POI leaves its cluster; a moved one leaves it and is inserted again;
//  - an inserted POI joins the cluster of its nearest POI (the cheapest place for it in that
//    round's cycle cover when its nearest neighbour is there);
//  - every cluster whose members changed has its cycle cover re-solved over its members (dense
//    Hungarian, poi/assignment.hpp): when the optimum has several cycles the cluster splits into
//    that many clusters of the same round, and its parent's members change in turn; a cluster
//    left with one member is replaced by it, one left empty disappears;
//  - the aggregates (centroid, bbox, size, worth and representative) are recomputed on the way
//    up to the root.
// Merges above the changed clusters stay as the rebuild made them, with their centroids moved:
// how far the result may drift from a rebuild is measured in tests/unit/poi/cluster_update_test
// and bench/cluster_bench (the quality figure at matched cluster counts).

#include "poi/cluster_tree.hpp"

#include <cstdint>
#include <vector>

namespace tourmap::poi {

struct ClusterEdits {
  // POIs by their index in the tree being updated (its leaves). The updated tree numbers its
  // leaves as the kept POIs in their old order, then the added ones in the order given here.
  std::vector<std::uint32_t> removed;
  std::vector<std::pair<std::uint32_t, ClusterPoint>> changed;  // new position and worth
  std::vector<ClusterPoint> added;
};

struct ClusterUpdateStats {
  std::size_t inserted = 0;    // added and moved POIs placed next to their nearest POI
  std::size_t resolved = 0;    // clusters whose cycle cover was re-solved
  std::size_t split = 0;       // clusters made by splits
  std::size_t dissolved = 0;   // clusters replaced by their only member or left empty
  bool rebuilt = false;        // the tree had no POI left to attach to: built from scratch
};

// Renumbers the leaves (POIs): leaf i becomes leaf new_index[i] (a permutation of 0..leaves-1),
// for a caller whose POI list orders them differently. Representatives are chosen again, since
// their ties go to the lowest index. Throws std::invalid_argument for a non-permutation.
void permute_leaves(ClusterTree& tree, const std::vector<std::uint32_t>& new_index);

// A copy of `tree` with room for updates that add POIs: growing a vector past its capacity
// copies it into fresh pages, which at 10^6 POIs costs more than the update itself.
ClusterTree copy_for_update(const ClusterTree& tree);

// Applies `edits` to `tree` in place. Throws std::invalid_argument (and leaves the tree as it
// was) for an index out of range, a POI both removed and changed or listed twice, or a
// non-finite position or a negative or non-finite worth.
ClusterUpdateStats update_cluster_tree(ClusterTree& tree, const ClusterEdits& edits, const ClusterOptions& options = {});

}  // namespace tourmap::poi
