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

#include "geo/projection.hpp"

#include <memory>
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

 private:
  struct Index;
  std::vector<XY> pos_;
  std::vector<double> bandwidth_;
  std::unique_ptr<Index> index_;
};

// Ranks 1..n from a score (higher score = more prominent = lower rank number), ties by index.
std::vector<double> ranks01_from_scores(const std::vector<double>& scores);

}  // namespace tourmap::metro
