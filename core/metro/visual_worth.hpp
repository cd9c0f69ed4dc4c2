#pragma once
// Visual worth (paper 5.4.1, eq. 5.1): a variable-bandwidth Gaussian kernel density estimate
// over POIs, where popular POIs (low rank number) and POIs close to a station get narrower,
// taller kernels:
//
//   vw(u) = 1/n * sum_i 1/h_i^2 * K(POI_i, u, h_i),  K = exp(-d^2 / (2 h_i^2)) / (2 pi h_i^2)
//   h_i   = k * (w_r * r_i + w_rho * rho_i)
//
// r_i is the POI's rank normalised to (0, 1] (rank / n), rho_i its distance to the nearest
// station in km (capped at 3). The paper writes d where a Gaussian has d^2; we use d^2.
// Kernels are cut at 4 h_i (weight below 3e-4) and indexed by their reach in an R-tree, so an
// evaluation costs the POIs that reach the point, not all POIs.
//
// Many points at once (at_points, raster): one evaluation costs the POIs in reach, which grows
// with the POI count (a 512 x 512 raster over 250,000 POIs is ~4 x 10^9 kernels). The batched
// calls first estimate the exact work, the sum over the points of the POIs in reach (a
// summed-area table of the points, one box count per POI: O(POIs + points)), then:
//
//   * within `work_budget` kernels: exact, every point through at()'s sum (the same doubles;
//     the sample cities' layouts, clusters and rasters up to 512 x 512 stay here). Should the
//     kernels actually visited pass 3 times the budget (points packed below the table's
//     resolution), the approximation takes over.
//   * above: an approximation whose cost does not grow with the POIs in reach. Bandwidths are
//     binned into levels H_l = h_min * 1.1^l. POIs narrower than a threshold level (chosen per
//     call to minimise an estimated cost) keep exact sums (bucket grids per band of h). Every
//     wider POI is split between the two levels around its h, with the mass shares that keep
//     the kernel's mass and second moment (linear in h^2), splatted with Catmull-Rom weights
//     onto a tiled grid (7 consecutive levels share one: cell = H / 3 for the narrowest of
//     them; 64 x 64-node tiles, only where POIs reach points), convolved with each level's
//     Gaussian (separable, cut at 4 H_l) and read back by Catmull-Rom interpolation. Cost:
//     O(POIs + points x (levels / 7 + narrow POIs in reach) + tiles x taps).
//
// Error bound of the approximation, per kernel, as a function of the POI's distance d from the
// point (the two sources: the level split, at most 0.9 % of the value up to 2 h and 1.9 % up
// to 3 h by analysis; the grid, at most 0.4 % at the peak, 0.7 % up to 2 h, 2.6 % up to 3 h
// measured on isolated kernels; together, measured on 400 isolated kernels over all levels:
// 1.1 %, 2.9 % and 0.9 % of the peak; tests/unit/metro/visual_worth_test.cpp checks these):
//   d <= 2 h_i:          at most kWorthKernelErrorWithin2h (1.5 %) of the kernel's value;
//   2 h_i < d <= 3 h_i:  at most kWorthKernelErrorWithin3h (4.5 %) of the kernel's value;
//   anywhere:            at most kWorthKernelErrorOfPeak (1.5 %) of the kernel's peak (beyond
//                        3 h, where the kernel is below 1.1 % of its peak, and at the 4 h cut,
//                        the error relative to the value itself grows large).
// Kernels are positive, so the error at a point is at most 1.5 % of the sum of the kernels
// within 2 h of it, plus 4.5 % of those at 2-3 h, plus 1.5 % of the peaks of those beyond.
// Values are clamped at 0 (the interpolation rings slightly below 0 where a kernel ends).
// Measured on whole fields against exact sums (bench/visual_worth_bench: synthetic cities of
// 10K-1M POIs, and the sample cities forced onto the approximation): max relative error
// 0.05-0.83 % where the value is at least 1e-3 of the maximum, mean 0.005-0.13 %, max error
// at most 0.05 % of the maximum (the raster's unit is 0.1 %).
//
// The batched calls poll util::check_stop() (about every 10^6 kernels or 2048 points, per
// level, grid and tile), so a request past its deadline or whose client went away stops with
// util::Stopped.

#include "geo/projection.hpp"

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace tourmap::metro {

using geo::XY;

struct WorthParams {
  double w_rank = 0.7;             // w_r
  double w_proximity = 0.3;        // w_rho
  double k_m = 1500.0;             // bandwidth constant k, metres
  double min_bandwidth_m = 60.0;   // floor for h_i (a POI next to a station at rank 1)
  double max_proximity_km = 3.0;   // rho_i cap
};

struct WorthSource {
  XY pos;               // metres (city projection)
  double rank01 = 1.0;  // r_i in (0, 1]
  double station_km = 0.0;  // rho_i before the cap
  // Beyond the paper: the tourist's interest in the POI's category (poi/interests.hpp), a
  // factor on its kernel in eq. 5.1 (>= 0; 1 keeps the paper's value exactly). n stays the
  // count of all POIs.
  double weight = 1.0;
};

// How a batched evaluation may go.
struct WorthEvalOptions {
  // Estimated kernel evaluations (sum over points of POIs in reach) up to which the batched
  // calls sum exactly through at(): ~0.1-0.3 s of CPU. A city of 3,000 POIs keeps exact
  // layouts and clusters (every POI in reach of every point: 3,500 x 3,000 kernels); the
  // sample cities' 512 x 512 rasters are ~1.5-1.8 x 10^6.
  double work_budget = 1.2e7;
  // Tests and benchmarks: when approximating, put every POI on the grids (no exact band).
  bool grids_only = false;
};

// The approximation's bound per kernel (see the header comment): its error relative to the
// kernel's value within 2 h and within 3 h of the POI, and relative to its peak anywhere.
inline constexpr double kWorthKernelErrorWithin2h = 0.015;
inline constexpr double kWorthKernelErrorWithin3h = 0.045;
inline constexpr double kWorthKernelErrorOfPeak = 0.015;

// What a batched evaluation did (benchmarks, tests, logs).
struct WorthEvalReport {
  bool exact = true;               // every value is at()'s
  double estimated_work = 0;       // kernels an exact evaluation would sum (estimate)
  std::size_t exact_sources = 0;   // POIs summed exactly (all of them when `exact`)
  std::size_t levels = 0;          // bandwidth levels on grids
  std::size_t tiles = 0;           // grid tiles computed
};

// An axis-aligned raster in projected metres: width x height cells over [lo, hi], evaluated at
// cell centres, rows from north (hi.y) to south, row-major (values[j * width + i]).
struct WorthRaster {
  XY lo, hi;
  std::size_t width = 0, height = 0;
};

class VisualWorth {
 public:
  VisualWorth(std::vector<WorthSource> sources, const WorthParams& params);
  ~VisualWorth();
  VisualWorth(VisualWorth&&) noexcept;

  // Raw eq. 5.1 value (1/m^4); 0 far from every POI, or without POIs.
  double at(XY u) const;
  std::size_t size() const { return bandwidth_.size(); }
  double bandwidth(std::size_t i) const { return bandwidth_[i]; }

  // at() for every point (see the header comment: exact within the work budget, else the
  // approximation with the bound above). Polls util::check_stop().
  std::vector<double> at_points(std::span<const XY> points, const WorthEvalOptions& options = {},
                                WorthEvalReport* report = nullptr) const;
  // at_points over the raster's cell centres.
  std::vector<double> raster(const WorthRaster& grid, const WorthEvalOptions& options = {},
                             WorthEvalReport* report = nullptr) const;

 private:
  struct Index;
  const Index& index() const;  // built on first use (the approximation does not need it)
  // at()'s kernel sum (before the 1/n); counts the index entries visited.
  double sum_at(XY u, std::size_t& visited) const;

  std::vector<XY> pos_;
  std::vector<double> bandwidth_;
  std::vector<double> weight_;  // per POI; empty when every weight is 1 (the paper's eq. 5.1)
  std::unique_ptr<Index> index_;
};

// Ranks 1..n from a score (higher score = more prominent = lower rank number), ties by index.
std::vector<double> ranks01_from_scores(const std::vector<double>& scores);

}  // namespace tourmap::metro
