#include "deform/deformer.hpp"
#include "util/elapsed.hpp"

#include <chrono>

namespace tourmap::deform {
namespace {
using util::Clock;
using util::ms_since;
}  // namespace

RunResult run(Prepared& p, const PlanarNetwork& net, const Targets& targets, const RunOptions& options,
              std::optional<std::size_t> rest_crossings) {
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
    if (options.relax && r.inverted_quads > 0) {
      r.relax_iterations = relax_foldovers(p, r.points, options.relax_iterations);
      r.inverted_quads = count_inverted_quads(*p.grid, r.points);
    }
  }
  r.nodes = road_nodes_from(p, r.points);
  r.place_ms = ms_since(t);
  r.residue = residue(net, targets, r.nodes);
  if (options.count_crossings) {
    auto after = count_crossings(r.nodes, net.edges);
    auto before = rest_crossings ? *rest_crossings : count_crossings(net.nodes, net.edges);
    r.crossings_added = after > before ? after - before : 0;
  }
  return r;
}

}  // namespace tourmap::deform
