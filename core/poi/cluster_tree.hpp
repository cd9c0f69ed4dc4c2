#pragma once
// Hungarian clustering (paper 5.4.4, after Lin et al.): the POIs start as clusters; each round
// solves a minimum cycle cover over the cluster centres (poi/assignment.hpp) and merges every
// cycle into one cluster, until one root remains. A flat array tree: leaves first, in input
// order, then the clusters in the order they were made, the root last.

#include "geo/projection.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tourmap::poi {

struct ClusterPoint {
  geo::XY pos;         // planar coordinates (metres or layout units)
  double worth = 0.0;  // visual worth vw, >= 0
};

// 80 bytes: worth comes before the 32-bit fields, so there is no padding.
struct ClusterNode {
  geo::XY center;                                  // centroid of its POIs
  geo::XY min, max;                                // bbox of its POIs
  double worth = 0.0;                              // vw(c): the largest worth of its POIs
  std::uint32_t size = 0;                          // POIs below (1 for a leaf)
  std::uint32_t representative = 0;                // the POI with that worth (ties: lowest index)
  std::int32_t parent = -1;                        // -1 for the root
  std::uint32_t first_child = 0, child_count = 0;  // range in ClusterTree::children
  std::uint32_t level = 0;                         // 0 = leaf, else the round that made it (> its children's)
};

struct ClusterTree {
  std::vector<ClusterNode> nodes;
  std::vector<std::uint32_t> children;
  std::uint32_t root = 0;  // meaningless when nodes is empty
  std::size_t leaves = 0;  // nodes[0..leaves) are the POIs, in input order
};

struct ClusterOptions {
  std::size_t dense_limit = 600;  // exact Hungarian while there are at most this many clusters
  std::size_t k = 8;              // candidates per cluster for the sparse assignment above that
};

// Throws std::invalid_argument for a non-finite position or a negative or non-finite worth.
ClusterTree build_cluster_tree(const std::vector<ClusterPoint>& points, const ClusterOptions& options = {});

}  // namespace tourmap::poi
