#pragma once
// Lines that share an edge drawn side by side, as the client's web/src/metro/bundles.ts does:
// each line its own polyline, moved sideways by its place in the edge's order (left to right
// as seen travelling from the edge's first point to its last) with mitred corners, and joined
// to itself through the stations. Page coordinates: px, y down.

#include "geo/projection.hpp"

#include <cstdint>
#include <vector>

namespace tourmap::map_export {

struct BundleEdge {
  std::uint32_t from = 0, to = 0;    // nodes
  std::vector<geo::XY> points;       // px, from -> to
  std::vector<std::uint32_t> order;  // line indices, left to right along `points`
};

// Per line: its offset polylines along the edges and its joins through nodes.
struct LinePieces {
  std::vector<std::vector<std::vector<geo::XY>>> strokes;  // [line] -> polylines
  std::vector<std::vector<std::vector<geo::XY>>> joins;    // [line] -> polylines
};

// The polyline moved `offset` px to its left (y down: left of east is up), with mitred corners;
// a corner too sharp to mitre ends one segment's offset and starts the next one's.
std::vector<geo::XY> offset_polyline(const std::vector<geo::XY>& points, double offset);

// Every line's pieces; `spacing` is the distance between neighbouring lines in px.
LinePieces bundle_pieces(const std::vector<BundleEdge>& edges, std::size_t line_count, double spacing);

}  // namespace tourmap::map_export
