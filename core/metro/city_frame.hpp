#pragma once
// A finished layout put back over the city (paper 5.4.3): the layout is aligned to the
// geography by a uniform scale and a translation (no rotation, which would break
// octilinearity), so clients can animate between the two; POIs, a regular mesh and the city's
// outline (the stations' convex hull: the data has no boundary) are warped into it.

#include "metro/layout_graph.hpp"

#include <vector>

namespace tourmap::metro {

// geo = scale * layout + shift.
struct ScaleShift {
  double scale = 1.0;
  XY shift{0, 0};
  XY apply(XY p) const { return {scale * p.x + shift.x, scale * p.y + shift.y}; }
};

// Uniform scale + translation taking `from` onto `to` in the least-squares sense.
ScaleShift fit_scale_translation(const std::vector<XY>& from, const std::vector<XY>& to);

struct PointPairs {
  std::vector<XY> geo, layout;  // the same points before and after warping (metres)
};

struct CityFrame {
  ScaleShift frame;                 // layout units -> metres
  std::vector<XY> nodes;            // layout node positions in metres (frame applied)
  std::vector<XY> poi_layout;       // POIs warped into the layout (metres)
  std::vector<bool> poi_outside;    // far beyond the network: not warped with confidence
  int mesh_side = 0;                // the mesh has mesh_side x mesh_side points, rows from south
  PointPairs mesh, outline;
};

// `geo_pos`: the network's nodes in metres; `layout`: the layout in layout units; `poi_xy`:
// POIs in metres.
CityFrame frame_city(const std::vector<XY>& geo_pos, const Layout& layout, const std::vector<XY>& poi_xy);

}  // namespace tourmap::metro
