#pragma once
// Where a batch of query points lies, for visual worth's batched evaluation (visual_worth.hpp):
// point counts on a grid with a summed-area table (the points in any box in O(1): the work an
// exact evaluation would do) and an occupancy pyramid (the cells that hold points, at any
// coarseness: where the approximation needs grid tiles).

#include "geo/projection.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace tourmap::metro::worth {

using geo::XY;

// Points between util::check_stop() calls in the batched loops.
inline constexpr std::size_t kStopEvery = 2048;

struct Bounds {
  XY lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  XY hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  void add(XY p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
};

// Where the points are: counts on a grid of up to 512 x 512 cells over their bounds, a
// summed-area table of them (box counts with the points spread evenly within a cell) and a
// pyramid of which cells hold points.
class PointDensity {
 public:
  // The points within `clip` (the others are not counted).
  PointDensity(std::span<const XY> pts, const Bounds& clip);


  // Points in [lo, hi] (fractional).
  double in_box(XY lo, XY hi) const { return below(hi.x, hi.y) - below(lo.x, hi.y) - below(hi.x, lo.y) + below(lo.x, lo.y); }

  // Calls f(lo, hi) for the bounds of every cell holding a point, on the coarsest level of an
  // occupancy pyramid (cells merged 2 x 2) whose cells are at most `size` metres.
  template <class F>
  void for_each_occupied(double size, F&& f) const {
    std::size_t k = 0;
    while (k + 1 < pyramid_.size() && cell_ * double(1 << (k + 1)) <= size) ++k;
    const Occupancy& o = pyramid_[k];
    const double c = cell_ * double(1 << k);
    for (int j = 0; j < o.gy; ++j)
      for (int i = 0; i < o.gx; ++i)
        if (o.used[static_cast<std::size_t>(j) * o.gx + i])
          f(XY{box_.lo.x + i * c, box_.lo.y + j * c}, XY{box_.lo.x + (i + 1) * c, box_.lo.y + (j + 1) * c});
  }

  const Bounds& bounds() const { return box_; }

 private:
  // Points with x' < x and y' < y: the table interpolated bilinearly (exact for even spread).
  double below(double x, double y) const {
    const double fx = std::clamp((x - box_.lo.x) / cell_, 0.0, double(gx_));
    const double fy = std::clamp((y - box_.lo.y) / cell_, 0.0, double(gy_));
    const int i = std::min(static_cast<int>(fx), gx_ - 1), j = std::min(static_cast<int>(fy), gy_ - 1);
    const double a = fx - i, b = fy - j;
    const std::size_t row = gx_ + 1;
    const double* s = &sat_[j * row + i];
    return (1 - b) * ((1 - a) * s[0] + a * s[1]) + b * ((1 - a) * s[row] + a * s[row + 1]);
  }

  struct Occupancy {
    int gx, gy;
    std::vector<std::uint8_t> used;
  };

  Bounds box_;
  double cell_ = 1;
  int gx_ = 1, gy_ = 1;
  std::vector<Occupancy> pyramid_;
  std::vector<std::uint32_t> counts_;
  std::vector<double> sat_;
};

}  // namespace tourmap::metro::worth
