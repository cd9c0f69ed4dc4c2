#pragma once
// The three map applications of paper 4.5 as deformation targets:
//   focus regions   -> a scale per road edge (eq. 4.9): edges in a region want Z times their length
//   mental maps     -> guide vertices pulled to a pattern's target points (eq. 4.6/4.7)
//   destination maps-> a route's vertices pulled onto a (simplified) sketch polyline

#include "deform/problem.hpp"

#include <memory>
#include <optional>
#include <vector>

namespace tourmap::deform {

struct Prepared;

struct FocusRegion {
  std::vector<XY> polygon;  // when non-empty: the region; else a circle
  XY center;
  double radius = 0.0;
  double scale = 1.0;  // Z
};

// An edge whose midpoint lies in a region takes that region's scale (the largest when in several).
std::vector<double> focus_edge_scales(const PlanarNetwork& net, const std::vector<FocusRegion>& regions);

// Nearest road node to each query point (CGAL kd-tree).
class NodeIndex {
 public:
  explicit NodeIndex(const std::vector<XY>& nodes);
  ~NodeIndex();
  std::uint32_t nearest(XY p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Douglas-Peucker: the polyline with every dropped point within `tolerance` of the kept ones.
// (A few lines; CGAL's polyline simplification works on constrained triangulations, which a
// sketch does not need.)
std::vector<XY> simplify_polyline(const std::vector<XY>& line, double tolerance);

// Destination map: route node i goes to the sketch point at the same fraction of arc length.
std::vector<Guide> route_to_sketch(const PlanarNetwork& net, const std::vector<std::uint32_t>& route,
                                   const std::vector<XY>& sketch);

// Guides sorted by node, as the prepared system expects; when several pull the same node the
// last one wins (clients cannot know where a drawn point snaps).
std::vector<Guide> sorted_guides(std::vector<Guide> guides);
std::vector<std::uint32_t> guide_nodes(const std::vector<Guide>& sorted);

// Where points of the original map land after a deformation: through the grid (embedded in
// their quad) or, for the edge-level method, moved like their nearest road node.
std::vector<XY> map_points(const Prepared& p, const std::vector<XY>& deformed_points,
                           const std::vector<XY>& deformed_nodes, const std::vector<XY>& rest_nodes,
                           const NodeIndex& index, const std::vector<XY>& queries);

}  // namespace tourmap::deform
