#pragma once
// Keeps a drawing's topology while its nodes move one at a time. The stress pre-layout uses it
// so that the octilinear router starts from the geography's crossings and circular orders:
// a pre-layout that moves a station across a line leaves the router only layouts with
// crossings the geography does not have.
//
// A simplified form of ImPrEd (Simonetto, Archambault, Auber, Bourqui 2011): instead of
// bounding every move by the distances to the surrounding edges, a proposed move is checked:
//   - each edge of the node crosses exactly the edges it crossed at the start;
//   - no other node lies in a triangle swept by one of the node's edges (a node cannot pass
//     over an edge unseen, e.g. around a line's end);
//   - the circular order of the edges at the node and at its neighbours stays as at the start.
// A check costs O(degree * (edges + nodes)).

#include "metro/layout_graph.hpp"

#include <cstdint>
#include <vector>

namespace tourmap::metro {

struct TopologyGuard {
  std::vector<std::vector<std::uint32_t>> incident;  // per node: its edges
  std::vector<std::vector<std::uint32_t>> crossing;  // per edge: the edges it crosses at the start, sorted
  std::vector<std::vector<std::uint32_t>> order;     // per node: neighbours counter-clockwise at the start
};

TopologyGuard make_topology_guard(const LayoutGraph& g, const std::vector<XY>& start);

// Whether moving `node` from pos[node] to `to` keeps the start's topology (see above).
bool move_keeps_topology(const TopologyGuard& guard, const LayoutGraph& g, const std::vector<XY>& pos,
                         std::uint32_t node, XY to);

// Segments ab and cd intersect (touching counts).
bool segments_intersect(XY a, XY b, XY c, XY d);

}  // namespace tourmap::metro
