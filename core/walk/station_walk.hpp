#pragma once
// The walk from a point to its nearest stations (issue 17, part 4): the point and every station
// are snapped to their nearest road vertex (walk/walk_graph.hpp); one Dijkstra search
// (Boost.Graph) from the point's vertex settles vertices in order of walking distance and stops
// as soon as the k nearest stations are known or the distance passes the cap.
//
// A walk's distance is the straight leg from the point to its road vertex, the road path, and
// the straight leg from the station's road vertex to the station; its path has those points.
// Bounded: the search settles only vertices within `max_m` of the point, and only stations
// within `max_m` of it in a straight line are snapped at all.

#include "walk/walk_graph.hpp"

#include <cstdint>
#include <vector>

namespace tourmap::walk {

struct WalkTarget {
  geo::LonLat pos;
  // Targets of one group are one destination (a station's platforms, say): a walk goes to the
  // nearest of them, and a group counts once towards k.
  std::uint32_t group = 0;
};

struct WalkQuery {
  geo::LonLat from;
  std::vector<WalkTarget> targets;
  std::size_t k = 3;        // groups wanted at most
  double max_m = 2000;      // walks longer than this are not taken
  double max_snap_m = 300;  // a point farther from any road vertex is not on the road network
};

struct Walk {
  std::uint32_t target = 0;  // index into WalkQuery::targets
  double distance_m = 0;     // along the path
  double straight_m = 0;     // geodesic, point to target: distance_m is never less
  std::vector<geo::LonLat> path;  // from the query point to the target
};

struct WalkResult {
  std::vector<Walk> walks;  // at most k, one per group, by distance (ties: target index)
  bool from_snapped = false;
  double from_snap_m = 0;   // the query point to its road vertex (when snapped)
  std::size_t candidates = 0;  // targets within max_m in a straight line and snapped
  std::size_t settled = 0;     // vertices the search settled
};

WalkResult nearest_walks(const WalkGraph& g, const WalkQuery& q);

}  // namespace tourmap::walk
