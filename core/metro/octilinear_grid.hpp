#pragma once
// The fast path to an octilinear layout (paper 5.4.2 asks for octilinearity; this is the
// heuristic that scales to hundreds of stations and seeds the MIP): each metro edge is routed
// as a shortest path through an octilinear grid graph (after Bast, Brosi and Storandt,
// "Metro Maps on Octilinear Grid Graphs", 2020), one after another:
//   - `start` must have the geography's topology (stress_layout with keep_topology does);
//   - degree-2 chains with the same lines are contracted and routed as one path; their
//     stations are put back along it at their share of the target length. An edge that
//     crosses another geographically stays a chain of its own;
//   - every station is placed first, on a free grid node near its start position, and its
//     edges get planned ports: distinct directions in their geographic circular order;
//   - a path costs its length plus a cost per bend (45, 90, 135 degrees) and per line that
//     bends through a station;
//   - paths use disjoint grid nodes and edges, and crossing diagonals exclude each other, so
//     the layout has no crossings, except that a path may cross (straight over, cheaply) the
//     path of an edge it crosses geographically, once;
//   - a path leaves and enters a station only through free ports; a port that breaks the
//     geographic circular order of the station's edges, or leaves too few free ports between
//     its neighbours for the edges still to come, costs a high penalty (unless no port keeps
//     the order, so that the route does not fail);
//   - a walled-in chain negotiates (after PathFinder, McMurchie and Ebeling 1995): it may go
//     through other paths at a price that grows each time a grid node is fought over, and
//     tears them up to be routed again;
//   - attempts: free routing, then on a grid twice as fine, then keeping paths near the
//     straight line between their ends; the best attempt (fewest overlaps, then fewest added
//     crossings) wins.
// Every segment is horizontal, vertical or diagonal. A chain still walled in when the
// negotiation budget is spent may cross any path, at a higher cost (an added crossing,
// reported); failing that it runs through other paths (overlapping them); only an edge with no
// route at all (e.g. a station with more than 8 edges) is drawn straight.

#include "metro/layout_graph.hpp"

#include <array>

namespace tourmap::metro {

struct GridRouteParams {
  double cell = 1.0;                             // grid spacing, layout units
  int candidate_radius = 3;                      // cells around a station's stretched position
  double move_cost = 1.0;                        // per cell a station moves from its position
  std::array<double, 4> bend_cost = {0.0, 1.0, 2.5, 6.0};  // turn by 0, 45, 90, 135 degrees
  double line_bend_weight = 1.0;                 // a line bending through a station, per line
  double order_penalty = 200.0;                  // leaving a station out of its circular order (or
                                                 // leaving too few ports for its later edges)
  double port_plan_weight = 2.0;                 // per 45 degrees away from the planned port
  double reserved_penalty = 6.0;                 // passing right next to another station
  double corridor_cost = 0.5;                    // per cell off the straight line between the ends...
  double corridor_slack = 3.0;                   // ...beyond this many cells, or this share of the
  double corridor_share = 0.0;                   // distance between the ends if that is more
  double crossing_cost = 2.0;                    // crossing a path it crosses geographically (cheap:
                                                 // going around instead distorts the map more)
  double added_crossing_cost = 60.0;             // walled in: crossing any other path
  double evict_cost = 10.0;                      // negotiating: going through another chain's path...
  double history_step = 1.0;                     // ...times 1 + history, which grows by this per fight
  std::size_t evictions_per_chain = 2;           // negotiation budget
  double overlap_cost = 40.0;                    // last resort: per grid node shared with another path
  std::size_t max_expansions = 30000;            // per path search, more for long ones (up to 8x):
                                                 // give up on walled-in routes fast
  double max_detour = 2.5;                       // a search gives up on paths costing more than this
  double detour_slack = 30.0;                    // times (the straight way + 10 cells), plus this
  double time_limit_ms = 8000.0;
  int attempts = 3;                              // on failure: retry on a finer grid
};

struct GridRouteReport {
  std::size_t chains = 0;          // routed paths (after contraction)
  std::size_t contracted_nodes = 0;
  std::size_t failed = 0;          // edges drawn straight
  std::size_t grid_nodes = 0;
  std::size_t ripups = 0;          // paths torn up to make way for a walled-in one (negotiation)
  std::size_t overlapping = 0;     // chains that could only be routed through other paths
  std::size_t crossing_routes = 0; // chains routed across paths they do not cross geographically
  std::size_t crossings = 0;       // pairs of edges that cross in the result
  std::size_t geo_crossings = 0;   // pairs of edges that cross in the geography
  int attempt = 1;
  bool timed_out = false;
  struct Attempt {                 // every attempt made, in order
    double cell = 0, ms = 0;
    std::size_t unrouted = 0;      // failed + overlapping chains
    std::size_t added = 0;         // added crossings + order violations
    std::size_t crossings = 0, ripups = 0;
  };
  std::vector<Attempt> attempts;
};

// `start` are the pre-layout positions (layout units) from stress_layout(scale_to_lengths);
// the geographic positions in `g.pos` give the circular orders and crossings to keep.
Layout route_octilinear(const LayoutGraph& g, const std::vector<XY>& start, const GridRouteParams& params,
                        GridRouteReport* report = nullptr);

}  // namespace tourmap::metro
