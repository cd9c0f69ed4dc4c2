#include "crowd/mds.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace tourmap::crowd {
namespace {

Eigen::MatrixXd distance_matrix(const Eigen::MatrixXd& points) {
  const Eigen::Index n = points.rows();
  Eigen::MatrixXd d(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) d(i, j) = (points.row(i) - points.row(j)).norm();
  return d;
}

TEST(ClassicalMds, UnitSquareIsRecoveredInTwoDimensions) {
  Eigen::MatrixXd square(4, 2);
  square << 0, 0, 1, 0, 1, 1, 0, 1;
  const Eigen::MatrixXd d = distance_matrix(square);
  const Eigen::MatrixXd x = classical_mds(d, 9);
  ASSERT_EQ(x.rows(), 4);
  ASSERT_EQ(x.cols(), 9);
  EXPECT_TRUE(distance_matrix(x).isApprox(d, 1e-9));
  // Two positive eigenvalues: the other seven columns are padding.
  EXPECT_GT(x.col(1).norm(), 0.5);
  EXPECT_NEAR(x.rightCols(7).norm(), 0.0, 1e-12);
}

TEST(ClassicalMds, CollinearPointsNeedOneDimension) {
  Eigen::MatrixXd line(5, 1);
  line << 0, 1, 3, 7, 7.5;
  const Eigen::MatrixXd d = distance_matrix(line);
  const Eigen::MatrixXd x = classical_mds(d, 3);
  EXPECT_NEAR(x.rightCols(2).norm(), 0.0, 1e-9);
  for (Eigen::Index i = 0; i < 5; ++i)
    for (Eigen::Index j = 0; j < 5; ++j) EXPECT_NEAR(std::abs(x(i, 0) - x(j, 0)), d(i, j), 1e-9);
}

TEST(ClassicalMds, FewerDimensionsThanTheDataKeepTheLargestSpread) {
  // A flat box: 10 x 1 x 0.01. Projected to 1 dimension the long axis must survive.
  Eigen::MatrixXd box(8, 3);
  for (int i = 0; i < 8; ++i) box.row(i) << (i & 1) * 10.0, ((i >> 1) & 1) * 1.0, ((i >> 2) & 1) * 0.01;
  const Eigen::MatrixXd x = classical_mds(distance_matrix(box), 1);
  ASSERT_EQ(x.cols(), 1);
  EXPECT_NEAR(std::abs(x(1, 0) - x(0, 0)), 10.0, 1e-9);
  EXPECT_NEAR(std::abs(x(2, 0) - x(0, 0)), 0.0, 1e-9);
  EXPECT_TRUE(distance_matrix(classical_mds(distance_matrix(box), 3)).isApprox(distance_matrix(box), 1e-9));
}

TEST(ClassicalMds, RejectsBadInput) {
  EXPECT_THROW(classical_mds(Eigen::MatrixXd::Zero(3, 2), 2), std::invalid_argument);
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(3, 3);
  EXPECT_THROW(classical_mds(d, 0), std::invalid_argument);
  d(0, 1) = 1;  // not symmetric
  EXPECT_THROW(classical_mds(d, 2), std::invalid_argument);
  d(1, 0) = 1;
  d(0, 2) = d(2, 0) = -1;
  EXPECT_THROW(classical_mds(d, 2), std::invalid_argument);
  d(0, 2) = d(2, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(classical_mds(d, 2), std::invalid_argument);
  EXPECT_THROW(classical_mds(Eigen::MatrixXd::Zero(3001, 3001), 2), std::invalid_argument);
  EXPECT_EQ(classical_mds(Eigen::MatrixXd(0, 0), 4).cols(), 4);
}

}  // namespace
}  // namespace tourmap::crowd
