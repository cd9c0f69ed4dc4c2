#pragma once
// The fast path to an octilinear layout (paper 5.4.2 asks for octilinearity; this is the
// heuristic that scales to hundreds of stations and seeds the MIP): each metro edge is routed
// as a shortest path through an octilinear grid graph (after Bast, Brosi and Storandt,
// "Metro Maps on Octilinear Grid Graphs", 2020), one after another:
//   - degree-2 chains with the same lines are contracted and routed as one path; their
//     stations are put back along it at their share of the target length;
//   - when a route fails, the next attempt routes the failed chains first, on a finer grid;
//   - every station is placed first, on a free grid node near its stretched position, and its
//     edges get planned ports: distinct directions in their geographic circular order;
//   - a path costs its length plus a cost per bend (45, 90, 135 degrees) and per line that
//     bends through a station;
//   - paths use disjoint grid nodes and edges, and crossing diagonals exclude each other, so
//     the layout has no crossings; a path leaves and enters a station only through free ports,
//     and a port out of the geographic circular order of the station's edges costs a penalty
//     (so order violations are rare and reported, instead of failed routes).
// Every segment is horizontal, vertical or diagonal. A chain that stays walled in after
// rip-ups is routed through other paths at a high cost (still octilinear; its crossings are
// reported); only an edge with no route at all (e.g. a station with more than 8 edges) is
// drawn straight.

#include "metro/layout_graph.hpp"

#include <array>

namespace tourmap::metro {

struct GridRouteParams {
  double cell = 1.0;                             // grid spacing, layout units
  int candidate_radius = 3;                      // cells around a station's stretched position
  double move_cost = 1.0;                        // per cell a station moves from its position
  std::array<double, 4> bend_cost = {0.0, 1.0, 2.5, 6.0};  // turn by 0, 45, 90, 135 degrees
  double line_bend_weight = 1.0;                 // a line bending through a station, per line
  double order_penalty = 20.0;                   // leaving a station out of its circular order
  double port_plan_weight = 2.0;                 // per 45 degrees away from the planned port
  double reserved_penalty = 6.0;                 // passing right next to another station
  double corridor_cost = 0.5;                    // per cell off the straight line between the ends...
  double corridor_slack = 3.0;                   // ...beyond this many cells, or this share of the
  double corridor_share = 0.0;                   // distance between the ends if that is more
  double overlap_cost = 40.0;                    // last resort: per grid node shared with another path
  std::size_t max_expansions = 400000;           // per path search: give up on hopeless routes fast
  double time_limit_ms = 8000.0;
  int attempts = 3;                              // on failure: retry on a finer grid
};

struct GridRouteReport {
  std::size_t chains = 0;          // routed paths (after contraction)
  std::size_t contracted_nodes = 0;
  std::size_t failed = 0;          // edges drawn straight
  std::size_t grid_nodes = 0;
  std::size_t ripups = 0;          // paths torn up to make way for a walled-in one
  std::size_t overlapping = 0;     // chains that could only be routed through other paths
  int attempt = 1;
  bool timed_out = false;
};

// `start` are the stretched positions (layout units) from stretch_to_lengths; the geographic
// positions in `g.pos` give the circular order.
Layout route_octilinear(const LayoutGraph& g, const std::vector<XY>& start, const GridRouteParams& params,
                        GridRouteReport* report = nullptr);

}  // namespace tourmap::metro
