#pragma once
// One deformation run on a prepared system: right-hand side for the request's targets, solve,
// place the road nodes, measure residue and foldovers; by default relax fold-overs and the
// crossings the drawn chords added.

#include "deform/foldover.hpp"
#include "deform/solver.hpp"

#include <optional>

namespace tourmap::deform {

struct RunOptions {
  SolveOptions solve;
  bool relax = true;              // run the foldover relaxation step (4.4.2) when a quad folded
  int relax_iterations = 100;
  bool untangle = true;           // with relax: smooth away road crossings the chords added (deform/untangle.hpp)
  int untangle_steps = 60;
  // Relaxing and untangling together stop after this long (what is left is reported): a
  // request with 2,000 guides pulled anywhere on Liechtenstein took 4 s without it.
  double correction_budget_ms = 250;
  bool snap_tjunctions = true;    // off only to measure what it changes (bench/deform_bench)
  bool count_crossings = false;   // road edge crossings added by the deformation (costly on big maps)
};

struct RunResult {
  std::vector<XY> points;  // grid vertices (grid method) or road nodes (edge method)
  std::vector<XY> nodes;   // deformed road nodes
  Eigen::VectorXd unknowns;  // for warm starts
  SolveReport solve;
  double rhs_ms = 0.0, place_ms = 0.0;
  double residue = 0.0;
  std::size_t inverted_quads = 0;
  std::optional<std::size_t> crossings_added;
  int relax_iterations = 0;
  int untangle_steps = 0;          // smoothing steps against added crossings
  std::size_t untangle_left = 0;   // new crossing pairs left when the steps ran out
};

RunResult run(Prepared& p, const PlanarNetwork& net, const Targets& targets, const RunOptions& options);

}  // namespace tourmap::deform
