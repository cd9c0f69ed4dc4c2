#pragma once
// Chain contraction for route_octilinear: degree-2 chains with the same lines are contracted
// and routed as one path (fewer, longer searches; no bends forced at minor stations); their
// stations are put back along the routed path at their share of the target length.

#include "metro/layout_graph.hpp"

#include <cstdint>
#include <vector>

namespace tourmap::metro::octi {

struct Chain {
  std::vector<std::uint32_t> nodes;  // anchor, interior..., anchor
  std::vector<std::uint32_t> edges;  // original edges along it
  std::vector<bool> forward;         // edge runs in chain direction
  std::vector<std::uint32_t> lines;  // sorted line set
};

std::vector<std::uint32_t> sorted_lines(std::vector<std::uint32_t> l);

// Every edge in exactly one chain. A chain ends at anchors: nodes not of degree 2, whose two
// edges carry different lines or lead to the same neighbour, one node per cycle of degree-2
// nodes, and the middle node of a chain that would return to its own anchor.
// `anchor` comes in with the nodes that must stay chain ends and goes out with all of them.
std::vector<Chain> contract_chains(const LayoutGraph& g, std::vector<bool>& anchor);

// The geographic direction (radians) in which chain `c` leaves its front or back anchor.
double end_angle(const LayoutGraph& g, const Chain& c, bool from_front);

// The arc-length share of the chain's target length (min_length) at each of its nodes: 0 at
// the front anchor, 1 at the back one (equal shares when the lengths are all 0).
std::vector<double> node_shares(const LayoutGraph& g, const Chain& c);

// Puts the chain's interior stations along its routed `path` (front anchor to back anchor) at
// their shares, and gives each of its edges its piece of the path (in the edge's direction).
void unroll_chain(const LayoutGraph& g, const Chain& c, const std::vector<XY>& path, Layout& layout);

// Point at arc-length fraction t along a polyline (its ends exactly at t = 0 and 1).
XY point_along(const std::vector<XY>& line, double t);

// The part of a polyline between arc fractions t0 < t1.
std::vector<XY> sub_polyline(const std::vector<XY>& line, double t0, double t1);

// Drops interior points where the direction does not change.
std::vector<XY> simplify_collinear(const std::vector<XY>& line);

}  // namespace tourmap::metro::octi
