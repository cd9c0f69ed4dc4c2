#pragma once
// Minimum cycle covers for Hungarian clustering (paper 5.4.4 step b, after Lin et al.): every
// point i gets a successor j, the sum of distances |p_i - p_j| is minimal, and the permutation's
// cycles become the next round's clusters. Cast as an assignment problem: rows are the points,
// columns their successors.

#include "geo/projection.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace tourmap::poi {

struct CycleCover {
  std::vector<std::uint32_t> successor;  // a permutation of 0..n-1
  double cost = 0.0;                     // the minimised total: distances plus self-loop penalties
  std::size_t self_loops = 0;            // points that stay alone (sparse only)
};

// Exact over the full distance matrix with self-assignment forbidden, so every cycle has at
// least two points (n < 2: the identity). Hungarian method, O(n^3) time and n^2 doubles: the
// paper's 120 POIs, and the last rounds of a big tree.
CycleCover min_cycle_cover_dense(const std::vector<geo::XY>& points);

// Scratch memory that a sequence of sparse covers reuses (the rounds of one cluster build): the
// buffers of a fresh 10^6-point cover cost more in page faults and zeroing than its kNN search.
struct SparseCoverScratch {
  struct Buffers;
  std::unique_ptr<Buffers> buffers;
  SparseCoverScratch();
  ~SparseCoverScratch();
};

// Candidates restricted to the k nearest other points, plus the arcs back from points that have
// this one among their k nearest, plus the point itself at self_loop_penalty(): a sparse
// assignment, always feasible (the identity), solved exactly over these candidates (augmenting
// row reduction, then successive shortest paths; see the .cpp), with the arc costs rounded to
// float (a relative 6e-8). With k >= n - 1 the penalty is never worth paying, so the cost equals
// the dense optimum. The points are sorted along a Hilbert curve first unless `in_hilbert_order`
// says they already are (hilbert_order): the result does not depend on the order, the speed does.
CycleCover min_cycle_cover_sparse(const std::vector<geo::XY>& points, std::size_t k, bool in_hilbert_order = false,
                                  SparseCoverScratch* scratch = nullptr);

// Staying alone costs 3x the distance to the farthest candidate plus the mean candidate
// distance (1 when all are 0). Above 2x the farthest candidate, so inserting the point into any
// cycle through its candidates (triangle inequality: <= 2x) or pairing it is always cheaper.
double self_loop_penalty(double farthest_candidate, double mean_candidate);

}  // namespace tourmap::poi
