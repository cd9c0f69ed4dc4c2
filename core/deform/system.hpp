#pragma once
// The deformation as one sparse least-squares problem, min ||A x - b||^2, over the free
// coordinates x of the deformation's points (grid vertices, or road nodes for the edge-level
// baseline). Rows are grouped by objective; only the road-edge and guide targets in b depend on
// a request, so A, its normal matrix and its factorization are prepared once and re-used.

#include "deform/problem.hpp"
#include "grid/embedding.hpp"
#include "grid/grid.hpp"

#include <Eigen/Sparse>

#include <array>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace tourmap::deform {

using SparseMatrix = Eigen::SparseMatrix<double>;

struct LinearSystem {
  SparseMatrix A;               // rows x free unknowns
  Eigen::VectorXd fixed_part;   // per row: the contribution of fixed coordinates (moved to b)
  Eigen::VectorXd base_target;  // per row: targets that do not depend on the request (smoothing)
  std::size_t road_rows = 0;    // rows [0, 2 * edges): road edges, x then y per edge
  std::size_t guide_row_begin = 0;  // rows [guide_row_begin, +2 * guides): guides, x then y
  double road_scale = 1.0;      // sqrt(w_RE)
  double guide_scale = 1.0;     // sqrt(w_GV)
};

enum class Method { grid, edges };

// Everything about a deformation that does not change while the user drags: the grid and the
// road embedding, the system matrix, its normal matrix and (lazily) its Cholesky factorization.
// Interior sample points of every road edge, embedded in the rest grid (deform/untangle.hpp).
struct EdgeSamples {
  std::vector<std::uint32_t> start;        // per edge: its first sample; start[edges] = total
  std::vector<grid::Embedding> samples;
  std::vector<float> clearance;            // per edge: rest distance to the nearest other road (capped)
  // Incidence, CSR: the edges with an endpoint or sample in each quad, the quads at each vertex.
  std::vector<std::uint32_t> quad_edges_start, quad_edges, vertex_quads_start, vertex_quads;
};

struct Prepared {
  Method method = Method::grid;
  std::optional<grid::Grid> grid;             // Method::grid only
  std::vector<grid::Embedding> embeddings;    // per road node, Method::grid only
  EdgeSamples edge_samples;                   // per road edge, Method::grid only
  std::vector<XY> rest;                       // points at rest: grid vertices, or road nodes
  std::vector<std::array<int, 2>> column;     // per point and axis: unknown index, or -1 if fixed
  std::vector<std::uint32_t> guide_nodes;     // the guide set the rows were built for
  LinearSystem system;
  SparseMatrix normal;                        // A^T A
  Eigen::VectorXd rest_unknowns;              // x at rest
  std::size_t support_edges = 0;
  double assembly_ms = 0.0;

  // Cholesky factorization of `normal`, computed once on first use (thread-safe).
  struct Factor;
  std::shared_ptr<const Factor> factor(double* factor_ms, bool* cached);
  // Approximate heap bytes held, the factorization included once computed (cache budgets).
  std::size_t memory_bytes() const;

  Prepared();
  ~Prepared();
  Prepared(Prepared&&) noexcept;
  Prepared& operator=(Prepared&&) noexcept;

 private:
  std::unique_ptr<std::mutex> factor_mutex_;
  std::shared_ptr<const Factor> factor_;
};

// Grid method (paper 4.4): unknowns are grid vertices. `guide_nodes` are the road nodes that
// will carry guide targets (their rows exist; the targets come with each request).
Prepared prepare_grid(const PlanarNetwork& net, grid::Grid grid, const std::vector<std::uint32_t>& guide_nodes,
                      const Weights& weights, Boundary boundary);

// Edge-level baseline (van Dijk & Haunert): unknowns are road nodes; the convex hull's nodes
// stay put (the map's outline) unless they carry a guide, and a 1e-6 pull to rest keeps
// disconnected pieces determined.
Prepared prepare_edges(const PlanarNetwork& net, const std::vector<std::uint32_t>& guide_nodes, const Weights& weights);

// A^T (b - fixed) for these targets.
Eigen::VectorXd right_hand_side(const Prepared& p, const PlanarNetwork& net, const Targets& targets);

// Positions of all points (grid vertices or road nodes) for the unknowns `x`.
std::vector<XY> points_from(const Prepared& p, const Eigen::VectorXd& x);
// Road node positions for those points.
std::vector<XY> road_nodes_from(const Prepared& p, const std::vector<XY>& points);

}  // namespace tourmap::deform
