#pragma once
// Map warping (paper 5.4.3): carries anything drawn on the geographic map (POIs, outlines, a
// regular mesh) into the octilinear layout, using the stations as control points.
//   1. Helmert transformation: 4 parameters (translation, one scale, one rotation) fitted by
//      least squares to the station positions.
//   2. The residual displacements left at the stations are interpolated by multiquadric
//      radial basis functions (eq. 5.5, 5.6).
// As printed, eq. 5.5/5.6 are implicit in the transformed point and singular at the control
// points (exponent -1/2, no shape parameter); we use Hardy's multiquadric sqrt(d^2 + c^2) in the
// Helmert-transformed plane, which interpolates the control points exactly and is explicit,
// with a constant term (and coefficients summing to 0) so it stays bounded far away.

#include "geo/projection.hpp"

#include <vector>

namespace tourmap::metro {

using geo::XY;

struct Helmert {
  double a = 1, b = 0, tx = 0, ty = 0;  // a = s cos(theta), b = s sin(theta)
  XY apply(XY p) const { return {a * p.x - b * p.y + tx, b * p.x + a * p.y + ty}; }
  double scale() const;
  double rotation() const;  // radians
};

// Least squares over point pairs; needs two distinct points (else the identity).
Helmert fit_helmert(const std::vector<XY>& from, const std::vector<XY>& to);

// The mean of the first n points.
inline XY centroid(const std::vector<XY>& pts, std::size_t n) {
  XY c{0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    c.x += pts[i].x / n;
    c.y += pts[i].y / n;
  }
  return c;
}

class Warp {
 public:
  Warp(const std::vector<XY>& from, const std::vector<XY>& to);
  XY operator()(XY p) const;
  const Helmert& helmert() const { return helmert_; }
  double shape() const { return c_; }  // multiquadric shape parameter c

 private:
  Helmert helmert_;
  std::vector<XY> centers_;           // control points after Helmert
  std::vector<double> alpha_, beta_;  // x and y coefficients
  XY offset_{0, 0};                   // constant term
  double c_ = 1.0;
};

}  // namespace tourmap::metro
