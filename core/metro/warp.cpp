#include "metro/warp.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tourmap::metro {

double Helmert::scale() const { return std::hypot(a, b); }
double Helmert::rotation() const { return std::atan2(b, a); }

Helmert fit_helmert(const std::vector<XY>& from, const std::vector<XY>& to) {
  std::size_t n = std::min(from.size(), to.size());
  if (n < 2) return {};
  // Centre both sets: the fit of (a, b) decouples from the translation.
  const XY cf = centroid(from, n), ct = centroid(to, n);
  double sxx = 0, a_num = 0, b_num = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double x = from[i].x - cf.x, y = from[i].y - cf.y, u = to[i].x - ct.x, v = to[i].y - ct.y;
    sxx += x * x + y * y;
    a_num += x * u + y * v;
    b_num += x * v - y * u;
  }
  if (sxx == 0) return {1, 0, ct.x - cf.x, ct.y - cf.y};
  Helmert h;
  h.a = a_num / sxx;
  h.b = b_num / sxx;
  h.tx = ct.x - (h.a * cf.x - h.b * cf.y);
  h.ty = ct.y - (h.b * cf.x + h.a * cf.y);
  return h;
}

Warp::Warp(const std::vector<XY>& from, const std::vector<XY>& to) : helmert_(fit_helmert(from, to)) {
  std::size_t n = std::min(from.size(), to.size());
  // Control points at distinct Helmert positions only (duplicates would make the system singular).
  std::vector<XY> residual;
  for (std::size_t i = 0; i < n; ++i) {
    XY h = helmert_.apply(from[i]);
    bool duplicate = std::any_of(centers_.begin(), centers_.end(),
                                 [&](const XY& c) { return std::hypot(c.x - h.x, c.y - h.y) < 1e-9; });
    if (duplicate) continue;
    centers_.push_back(h);
    residual.push_back({to[i].x - h.x, to[i].y - h.y});
  }
  std::size_t m = centers_.size();
  if (m == 0) return;
  // Shape parameter: the mean nearest-neighbour spacing of the control points.
  double spacing = 0;
  for (std::size_t i = 0; i < m; ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < m; ++j)
      if (i != j) best = std::min(best, std::hypot(centers_[i].x - centers_[j].x, centers_[i].y - centers_[j].y));
    if (std::isfinite(best)) spacing += best / m;
  }
  c_ = spacing > 0 ? spacing : 1.0;
  // [Phi 1; 1^T 0] [alpha; c0] = [r; 0]: the constant term and sum(alpha) = 0 keep the
  // interpolant bounded far from the control points (POIs outside the network stay sane).
  Eigen::MatrixXd phi = Eigen::MatrixXd::Zero(m + 1, m + 1);
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = 0; j < m; ++j) {
      double dx = centers_[i].x - centers_[j].x, dy = centers_[i].y - centers_[j].y;
      phi(i, j) = std::sqrt(dx * dx + dy * dy + c_ * c_);
    }
    phi(i, m) = phi(m, i) = 1.0;
  }
  Eigen::VectorXd rx = Eigen::VectorXd::Zero(m + 1), ry = Eigen::VectorXd::Zero(m + 1);
  for (std::size_t i = 0; i < m; ++i) {
    rx[i] = residual[i].x;
    ry[i] = residual[i].y;
  }
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(phi);
  Eigen::VectorXd ax = lu.solve(rx), by = lu.solve(ry);
  alpha_.assign(ax.data(), ax.data() + m);
  beta_.assign(by.data(), by.data() + m);
  offset_ = {ax[static_cast<Eigen::Index>(m)], by[static_cast<Eigen::Index>(m)]};
}

XY Warp::operator()(XY p) const {
  XY h = helmert_.apply(p);
  double dx = offset_.x, dy = offset_.y;
  for (std::size_t j = 0; j < centers_.size(); ++j) {
    double ex = h.x - centers_[j].x, ey = h.y - centers_[j].y;
    double phi = std::sqrt(ex * ex + ey * ey + c_ * c_);  // eq. 5.5 / 5.6 (multiquadric basis)
    dx += alpha_[j] * phi;
    dy += beta_[j] * phi;
  }
  return {h.x + dx, h.y + dy};
}

}  // namespace tourmap::metro
