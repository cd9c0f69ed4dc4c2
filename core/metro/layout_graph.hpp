#pragma once
// The metro network as the layout algorithms see it: nodes with planar positions (metres in
// the city projection), edges with the lines they carry and a minimum layout length (paper
// eq. 5.3/5.4), and the result: node positions and one octilinear polyline per edge.

#include "geo/projection.hpp"
#include "model/metro.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tourmap::metro {

using geo::XY;

struct LayoutGraph {
  std::vector<XY> pos;                                         // metres
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;  // node indices
  std::vector<std::vector<std::uint32_t>> edge_lines;          // line indices per edge
  std::vector<double> min_length;                              // per edge, layout units (eq. 5.4)
};

struct Layout {
  std::vector<XY> pos;                  // layout units, y up
  std::vector<std::vector<XY>> paths;   // per edge: from edges[i].first to .second, >= 2 points
  std::string method;                   // "grid" | "mip" | ...
  std::string status;                   // "ok", "optimal", "time_limit", "incomplete", ...
};

// Minimum edge lengths from visual worth (eq. 5.4): l_uv = l_const * (vw(u) + vw(v)) / 2, with vw
// normalised to mean 1 over the nodes (so the average edge keeps l_const) and clamped to
// [0.5, 2.5] * l_const so that no edge vanishes (crowding the octilinear grid) or dwarfs the map.
std::vector<double> visual_worth_lengths(const LayoutGraph& g, const std::vector<double>& node_worth, double l_const);

// The network in the plane of `projection`, every edge of length `length`, stations at one
// position moved 15 m apart (separate_coincident: a layout cannot draw them both).
LayoutGraph layout_graph_of(const model::MetroNetwork& net, const geo::LocalProjection& projection, double length = 10.0);

// Nodes at the same position are moved apart by `gap` metres around their centre (a layout
// cannot place two stations on one point); returns how many moved.
std::size_t separate_coincident(LayoutGraph& g, double gap);

}  // namespace tourmap::metro
