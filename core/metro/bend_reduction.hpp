#pragma once
// Fewer bends in an octilinear layout, after the grid router (metro/octilinear_grid.hpp).
//
// The router draws every edge as a shortest path on a grid whose cells are a fraction of an
// edge, so paths pick up short jogs and staircases that cost nothing in its metric. A metro map
// is read along its lines: what matters are the bends between two interchanges (or an
// interchange and a terminus). This pass works on exactly those: the chains of the drawing,
// maximal paths through stations of degree 2 between two anchors (nodes of degree != 2).
//
//   - a chain is redrawn with the fewest bends its anchors allow: straight when they lie on a
//     common octilinear line, else one bend (or a symmetric Z), its stations spread along it
//     at their share of the chain's target length (eq. 5.4 lengths);
//   - an anchor moves (to a point where an incident chain becomes straight, two chains meet
//     straight, or a small step) when its chains, redrawn, lower the objective
//         w_bend * bends + w_turn * sharp turns + w_displacement * sum |p - geo fit|^2 / l^2
//       + w_length * sum ln(length / target)^2
//       + w_gap * sum max(0, gap - clearance) / gap   (over chains, anchors and edges),
//     where gap is `gap_share` of the mean edge as it is now and a chain's clearance is its
//     stations' distance to stations they are not joined to and to edges they are not on (an
//     edge's own length is its stations' clearance to the next edge along the line);
//   - every change keeps the drawing valid: no crossing that was not there, each anchor's edges
//     leave in distinct directions in the same circular order, no clearance below the gap
//     where it was not already (and there no lower than it was), no edge shorter than the gap
//     or `min_edge_share` of its target (unless it started shorter), chains no shorter than
//     `min_length_share` of their target.
// Two phases: bends first, when a chain may come closer to another than that one's floor as
// long as the drawing's smallest clearance does not drop; then the geography and the clearance,
// without adding a bend, where no chain may crowd another below its floor.
// A cycle (a chain from an anchor back to it, as Heathrow's loop) is split at a middle station
// so that the search can move its stations.
// A local search: a phase stops when a round improves nothing, after its number of rounds, or
// at the time limit (rounds end it the same way on any machine; the time limit does not).

#include "metro/layout_graph.hpp"

#include <cstddef>

namespace tourmap::metro {

struct BendReductionParams {
  double gap_share = 0.5;          // clearance, in mean edge lengths (the "breathing" rule)
  double gap_margin = 1.12;        // ...asked with this margin (the mean edge still moves after it is measured)
  double min_length_share = 0.5;   // chain length >= this * its target length...
  double min_edge_share = 0.5;     // ...and every edge's >= this * its own
  double w_bend = 1.0;
  double w_gap = 2.0;              // per clearance (or edge) short of the gap, times the shortfall's share
  double w_gap_polish = 8.0;       // the same in the second phase
  double w_turn = 0.15;            // per 45 degrees of a bend's turn beyond the first 45
  double w_displacement = 0.05;    // per squared target length of a node's distance from the geography
  double w_displacement_polish = 0.3;  // the same in the second phase, which may not add bends...
  double polish_share = 0.3;           // ...and gets this share of the time; a bend removed
  double polish_bend_factor = 30.0;    // there is worth this many first-phase ones (none may be added)
  double w_length = 0.5;           // per squared log of an edge's length over its target...
  double longer_share = 0.2;       // ...times this when it is longer
  double move_radius = 1.5;        // anchor moves, in mean target lengths
  std::size_t evaluations_per_anchor = 24;  // candidate positions fully evaluated per anchor and round
  int max_rounds = 12;             // the first phase's rounds...
  int polish_max_rounds = 12;      // ...and the second's
  double time_limit_ms = 250.0;     // of this thread's CPU time (load on other cores does not count)
};

struct BendReductionReport {
  std::size_t chains = 0;
  std::size_t bends_before = 0, bends_after = 0;  // along chains (the bends a reader sees)
  std::size_t reshaped = 0;        // chains redrawn with anchors in place
  std::size_t moved = 0;           // anchor moves accepted
  int rounds = 0;
  double time_ms = 0;              // wall time
  bool timed_out = false;
};

// `g` gives the geography (g.pos) and the target lengths (g.min_length); `layout` is changed in
// place (positions and paths; method and status stay).
void reduce_bends(const LayoutGraph& g, Layout& layout, const BendReductionParams& params = {},
                  BendReductionReport* report = nullptr);

}  // namespace tourmap::metro
