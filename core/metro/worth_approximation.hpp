#pragma once
// The approximation behind visual worth's batched evaluation above its work budget: the method
// and its error bound are in visual_worth.hpp's header comment. Separate from the exact sums so
// that each file holds one method.

#include "metro/worth_density.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace tourmap::metro::worth {

struct ApproximationReport {
  std::size_t exact_sources = 0;  // narrow POIs summed exactly (exact bands)
  std::size_t levels = 0;         // bandwidth levels on grids
  std::size_t tiles = 0;          // grid tiles computed
};

// Adds eq. 5.1's sum over the POIs (`pos`, `bandwidth`, each kernel times `weight`, empty:
// 1; without the 1/n) at each point to
// `out` (sized like `points`). `density` describes the points, `exact_work[i]` the kernels POI
// i would cost summed exactly (it picks which POIs stay exact); `grids_only` puts every POI on
// the grids. Polls util::check_stop().
ApproximationReport approximate_worth(const std::vector<XY>& pos, const std::vector<double>& bandwidth,
                                      const std::vector<double>& weight, std::span<const XY> points, const PointDensity& density,
                                      const std::vector<double>& exact_work, bool grids_only,
                                      std::vector<double>& out);

}  // namespace tourmap::metro::worth
