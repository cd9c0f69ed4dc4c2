#pragma once
// How close the layout puts things that should be apart: the smallest distance between two
// nodes not joined by an edge, or between a node and the path of an edge that does not end at
// it. A small gap reads as a station on the wrong line or two stations merged.

#include "metro/layout_graph.hpp"

namespace tourmap::metro {

// Layout units; +infinity when there is no such pair (e.g. a single edge). A uniform grid over
// the layout keeps it near linear in the nodes and path length (London: 300 stations).
double min_station_gap(const LayoutGraph& g, const Layout& layout);

}  // namespace tourmap::metro
