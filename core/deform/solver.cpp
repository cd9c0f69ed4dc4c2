#include "deform/solver.hpp"
#include "util/elapsed.hpp"
#include "util/stop.hpp"

#include <Eigen/SparseCholesky>

#include <chrono>
#include <stdexcept>

namespace tourmap::deform {

struct Prepared::Factor {
  Eigen::SimplicialLDLT<SparseMatrix> ldlt;
};

std::shared_ptr<const Prepared::Factor> Prepared::factor(double* factor_ms, bool* cached) {
  std::lock_guard lock(*factor_mutex_);
  if (factor_) {
    if (cached) *cached = true;
    if (factor_ms) *factor_ms = 0.0;
    return factor_;
  }
  auto start = std::chrono::steady_clock::now();
  auto f = std::make_shared<Factor>();
  f->ldlt.compute(normal);
  if (f->ldlt.info() != Eigen::Success) throw std::runtime_error("Cholesky factorization failed (system not positive definite)");
  factor_ = f;
  if (cached) *cached = false;
  if (factor_ms) *factor_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return factor_;
}

namespace {
using util::Clock;
using util::ms_since;

template <class T>
std::size_t vector_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

std::size_t sparse_bytes(const SparseMatrix& m) {
  // values (double) + inner indices (int) per non-zero, outer index per column.
  return static_cast<std::size_t>(m.nonZeros()) * (sizeof(double) + sizeof(int)) +
         static_cast<std::size_t>(m.outerSize() + 1) * sizeof(int);
}

}  // namespace

std::size_t Prepared::memory_bytes() const {
  std::size_t bytes = sizeof(Prepared);
  if (grid) {
    const auto& g = *grid;
    bytes += vector_bytes(g.vertices) + g.on_boundary.capacity() / 8 + vector_bytes(g.neighbors) +
             vector_bytes(g.quads) + vector_bytes(g.tjunctions) + vector_bytes(g.cell_quad);
  }
  bytes += vector_bytes(embeddings) + vector_bytes(edge_samples.start) + vector_bytes(edge_samples.samples) + vector_bytes(edge_samples.clearance) + vector_bytes(edge_samples.quad_edges_start) +
             vector_bytes(edge_samples.quad_edges) + vector_bytes(edge_samples.vertex_quads_start) +
             vector_bytes(edge_samples.vertex_quads) + vector_bytes(rest) + vector_bytes(column) + vector_bytes(guide_nodes);
  bytes += sparse_bytes(system.A) + sparse_bytes(normal);
  bytes += static_cast<std::size_t>(system.fixed_part.size() + system.base_target.size() + rest_unknowns.size()) *
           sizeof(double);
  std::lock_guard lock(*factor_mutex_);
  if (factor_) {
    // L's non-zeros, D, and the permutation (two index vectors).
    const auto n = static_cast<std::size_t>(normal.rows());
    bytes += sparse_bytes(factor_->ldlt.matrixL().nestedExpression()) + n * (sizeof(double) + 2 * sizeof(int));
  }
  return bytes;
}

Eigen::VectorXd conjugate_gradient(const SparseMatrix& N, const Eigen::VectorXd& rhs, const Eigen::VectorXd& x0,
                                   const SolveOptions& options, SolveReport& report) {
  auto start = Clock::now();
  Eigen::VectorXd inv_diag = N.diagonal().cwiseInverse();
  Eigen::VectorXd x = x0;
  Eigen::VectorXd r = rhs - N * x;
  Eigen::VectorXd z = inv_diag.cwiseProduct(r);
  Eigen::VectorXd d = z;
  double rz = r.dot(z);
  double rhs_norm = rhs.norm();
  double stop = options.tolerance * (rhs_norm > 0 ? rhs_norm : 1.0);
  report.iterations = 0;
  report.converged = r.norm() <= stop;
  Eigen::VectorXd Nd(x.size());
  while (!report.converged && report.iterations < options.max_iterations) {
    Nd.noalias() = N * d;
    double dNd = d.dot(Nd);
    if (dNd <= 0) break;  // no progress possible (semidefinite direction)
    double alpha = rz / dNd;
    x += alpha * d;
    r -= alpha * Nd;
    ++report.iterations;
    if (r.norm() <= stop) {
      report.converged = true;
      break;
    }
    z = inv_diag.cwiseProduct(r);
    double rz_next = r.dot(z);
    d = z + (rz_next / rz) * d;
    rz = rz_next;
    if ((report.iterations & 15) == 0) {
      util::check_stop();  // the request's deadline, or its client left
      if (ms_since(start) > options.time_limit_ms) break;
    }
  }
  report.relative_residual = (rhs - N * x).norm() / (rhs_norm > 0 ? rhs_norm : 1.0);
  return x;
}

Eigen::VectorXd solve(Prepared& p, const Eigen::VectorXd& rhs, const SolveOptions& options, SolveReport& report) {
  report.kind = options.kind;
  if (options.kind == SolverKind::cg) {
    auto start = Clock::now();
    const Eigen::VectorXd& x0 =
        options.warm_start && options.warm_start->size() == rhs.size() ? *options.warm_start : p.rest_unknowns;
    auto x = conjugate_gradient(p.normal, rhs, x0, options, report);
    report.solve_ms = ms_since(start);
    return x;
  }
  auto factor = p.factor(&report.factor_ms, &report.factor_cached);
  auto start = Clock::now();
  Eigen::VectorXd x = factor->ldlt.solve(rhs);
  report.solve_ms = ms_since(start);
  double rhs_norm = rhs.norm();
  report.relative_residual = (p.normal * x - rhs).norm() / (rhs_norm > 0 ? rhs_norm : 1.0);
  report.converged = x.allFinite();
  return x;
}

}  // namespace tourmap::deform
