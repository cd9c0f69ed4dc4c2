#pragma once
// Solvers for the normal equations A^T A x = A^T b (paper 4.4.2): a sparse Cholesky (LDL^T)
// whose factorization is kept in the Prepared system, so a new focus scale or guide target
// costs one back-substitution; and conjugate gradient as in the paper, with a warm start, an
// iteration cap, a tolerance and a time limit.

#include "deform/system.hpp"

namespace tourmap::deform {

enum class SolverKind { cholesky, cg };

struct SolveOptions {
  SolverKind kind = SolverKind::cholesky;
  int max_iterations = 20000;      // CG
  double tolerance = 1e-8;         // CG: stop at ||r|| <= tolerance * ||rhs||
  double time_limit_ms = 10000.0;  // CG: stop with the best iterate when exceeded
  const Eigen::VectorXd* warm_start = nullptr;  // CG: initial guess (else the rest state)
};

struct SolveReport {
  SolverKind kind = SolverKind::cholesky;
  int iterations = 0;
  bool converged = false;
  double relative_residual = 0.0;  // ||A^T A x - A^T b|| / ||A^T b||
  double factor_ms = 0.0;          // 0 when the factorization was re-used
  double solve_ms = 0.0;
  bool factor_cached = false;
};

Eigen::VectorXd solve(Prepared& p, const Eigen::VectorXd& rhs, const SolveOptions& options, SolveReport& report);

// Jacobi-preconditioned conjugate gradient on a symmetric positive (semi)definite matrix.
// Eigen's ConjugateGradient has no time limit or progress report, which an interactive
// service needs, so this is the textbook loop (Shewchuk, "An Introduction to the Conjugate
// Gradient Method Without the Agonizing Pain", B3).
Eigen::VectorXd conjugate_gradient(const SparseMatrix& N, const Eigen::VectorXd& rhs, const Eigen::VectorXd& x0,
                                   const SolveOptions& options, SolveReport& report);

}  // namespace tourmap::deform
