#include "crowd/mds.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <stdexcept>
#include <string>

namespace tourmap::crowd {

namespace {
constexpr Eigen::Index kMaxPoints = 3000;  // O(n^3) eigen decomposition: ~10 s at this size
}

Eigen::MatrixXd classical_mds(const Eigen::MatrixXd& distances, int dims) {
  const Eigen::Index n = distances.rows();
  if (distances.cols() != n) throw std::invalid_argument("classical_mds: the distance matrix is not square");
  if (dims < 1) throw std::invalid_argument("classical_mds: dims must be >= 1, got " + std::to_string(dims));
  if (n > kMaxPoints)
    throw std::invalid_argument("classical_mds: " + std::to_string(n) + " points, more than " +
                                std::to_string(kMaxPoints));
  if (!distances.allFinite()) throw std::invalid_argument("classical_mds: non-finite distance");
  if (n == 0) return Eigen::MatrixXd::Zero(0, dims);
  const double scale = std::max(1.0, distances.cwiseAbs().maxCoeff());
  if ((distances - distances.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
    throw std::invalid_argument("classical_mds: the distance matrix is not symmetric");
  if ((distances.array() < 0).any()) throw std::invalid_argument("classical_mds: negative distance");

  // Double centring of the squared distances.
  const Eigen::MatrixXd sq = distances.array().square().matrix();
  const Eigen::VectorXd row_mean = sq.rowwise().mean();
  const double grand_mean = row_mean.mean();
  Eigen::MatrixXd b = sq;
  b.colwise() -= row_mean;
  b.rowwise() -= row_mean.transpose();  // sq is symmetric: column means = row means
  b.array() += grand_mean;
  b *= -0.5;

  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(b);
  if (eig.info() != Eigen::Success) throw std::invalid_argument("classical_mds: eigen decomposition failed");
  const Eigen::VectorXd& values = eig.eigenvalues();  // ascending
  const double largest = values.cwiseAbs().maxCoeff();
  const double tolerance = 1e-10 * std::max(largest, 1e-300);
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, dims);
  for (int k = 0; k < dims && k < n; ++k) {
    const Eigen::Index i = n - 1 - k;
    if (values[i] <= tolerance) break;  // the rest are not positive: padding zeros
    out.col(k) = eig.eigenvectors().col(i) * std::sqrt(values[i]);
  }
  return out;
}

}  // namespace tourmap::crowd
