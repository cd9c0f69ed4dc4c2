#include "deform/deformer.hpp"
#include "deform/untangle.hpp"
#include "util/elapsed.hpp"

#include <chrono>

namespace tourmap::deform {
namespace {
using util::Clock;
using util::ms_since;
}  // namespace

RunResult run(Prepared& p, const PlanarNetwork& net, const Targets& targets, const RunOptions& options) {
  RunResult r;
  auto t = Clock::now();
  auto rhs = right_hand_side(p, net, targets);
  r.rhs_ms = ms_since(t);
  r.unknowns = solve(p, rhs, options.solve, r.solve);
  t = Clock::now();
  r.points = points_from(p, r.unknowns);
  if (p.method == Method::grid) {
    if (options.snap_tjunctions) snap_tjunctions(*p.grid, r.points);
    r.inverted_quads = count_inverted_quads(*p.grid, r.points);
    // Unfold, then take the crossings out; smoothing against crossings could fold a quad again
    // (it never did on the shared extracts), hence a few rounds.
    const auto until = Clock::now() + std::chrono::microseconds(static_cast<long long>(options.correction_budget_ms * 1000));
    for (int round = 0; options.relax && round < 3; ++round) {
      if (r.inverted_quads > 0) {
        r.relax_iterations += relax_foldovers(p, r.points, options.relax_iterations, until);
        r.inverted_quads = count_inverted_quads(*p.grid, r.points);
      }
      if (!options.untangle) break;
      std::vector<XY> nodes;
      const auto u = untangle_crossings(p, net, r.points, nodes, options.untangle_steps, until);
      r.untangle_steps += u.steps;
      r.untangle_left = u.left;
      if (u.steps == 0) break;
      r.inverted_quads = count_inverted_quads(*p.grid, r.points);
      if (r.inverted_quads == 0 || Clock::now() >= until) break;
    }
  }
  r.nodes = road_nodes_from(p, r.points);
  r.place_ms = ms_since(t);
  r.residue = residue(net, targets, r.nodes);
  if (options.count_crossings) r.crossings_added = count_added_crossings(net, r.nodes);
  return r;
}

}  // namespace tourmap::deform
