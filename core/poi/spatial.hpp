#pragma once
// Spatial helpers for the sparse cycle cover (paper 5.4.4 at 10^5..10^6 POIs): a Hilbert-curve
// order and the k nearest neighbours of every point.
//
// Written here rather than taken from CGAL (kd-tree, hilbert_sort) or nanoflann: on 10^6
// GeoNames-like points CGAL's k-neighbour search took 1.5 s, nanoflann's 1.05 s and CGAL's
// Hilbert sort 0.39 s, against a cluster round that must fit in a few hundred milliseconds.
// Points that are already in Hilbert order make a packed R-tree for free (boxes over runs of
// consecutive points, as in flatbush or a packed Hilbert R-tree), so that is what k_nearest uses.

#include "geo/projection.hpp"
#include "util/fork_join.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tourmap::poi {

struct Neighbours {
  std::size_t k = 0;                 // per point: min(requested k, n - 1)
  std::vector<std::uint32_t> index;  // row-major n x k, nearest first; never the point itself
};

// The k nearest other points of every point (ties at equal distance broken arbitrarily).
// Correct for points in any order, and fastest for points in hilbert_order: the packed tree's
// boxes are runs of consecutive points. Non-finite coordinates are not allowed.
Neighbours k_nearest(const std::vector<geo::XY>& points, std::size_t k);
// The same into `out`, reusing its memory, on the threads of `pool` when given (the result does
// not depend on them).
void k_nearest(const std::vector<geo::XY>& points, std::size_t k, Neighbours& out, util::ForkJoin* pool = nullptr);

// Point indices along a Hilbert curve over the points' bounding box (a 2^16 x 2^16 grid; points
// in one cell keep their input order): numbering points in this order keeps neighbours close in
// memory.
// With `keys`, also the curve index of each point in that order (equal for points in one cell).
std::vector<std::uint32_t> hilbert_order(const std::vector<geo::XY>& points, std::vector<std::uint32_t>* keys = nullptr);

}  // namespace tourmap::poi
