#pragma once
// Classical (Torgerson) multi-dimensional scaling, the pose space reduction of sec. 3.4:
// points whose Euclidean distances reproduce a given distance matrix as well as `dims`
// dimensions allow (exactly, if the distances are Euclidean and dims >= their rank).

#include <Eigen/Core>

namespace tourmap::crowd {

// `distances`: symmetric n x n, zero diagonal, finite, n <= 3000 (a dense eigen decomposition).
// Returns n x dims coordinates: B = -1/2 J D^2 J (J = I - 11^T/n), the eigenvectors of the
// largest positive eigenvalues scaled by sqrt(eigenvalue); columns beyond the number of
// positive eigenvalues are zero. Throws std::invalid_argument on bad input.
Eigen::MatrixXd classical_mds(const Eigen::MatrixXd& distances, int dims);

}  // namespace tourmap::crowd
