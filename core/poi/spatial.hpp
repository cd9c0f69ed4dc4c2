#pragma once
// Spatial helpers for the sparse cycle cover (paper 5.4.4 at 10^5..10^6 POIs), both from CGAL's
// spatial searching and sorting: k nearest neighbours (kd-tree) and a Hilbert-curve order.

#include "geo/projection.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tourmap::poi {

struct Neighbours {
  std::size_t k = 0;                 // per point: min(requested k, n - 1)
  std::vector<std::uint32_t> index;  // row-major n x k, nearest first; never the point itself
};

// The k nearest other points of every point.
Neighbours k_nearest(const std::vector<geo::XY>& points, std::size_t k);

// Point indices along a Hilbert curve: numbering points in this order keeps neighbours close
// in memory.
std::vector<std::uint32_t> hilbert_order(const std::vector<geo::XY>& points);

}  // namespace tourmap::poi
