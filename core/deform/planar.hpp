#pragma once
// A road network in the plane where deformation happens: the network's local transverse
// Mercator projection, scaled so that the longer side of its bbox is 1000 map units. Residues
// and weights are in these units, so they compare across networks of any size.

#include "geo/projection.hpp"
#include "model/road.hpp"

#include <cstdint>
#include <utility>
#include <vector>

namespace tourmap::deform {

using geo::XY;

inline constexpr double kMapUnits = 1000.0;

// lon/lat <-> map units.
struct MapTransform {
  geo::LocalProjection projection;
  XY center;               // projected metres at the bbox centre
  double metres_per_unit = 1.0;

  XY to_map(geo::LonLat p) const;
  geo::LonLat to_lonlat(XY p) const;
};

// Map units -> lon/lat for many points: bilinear interpolation in a table of exact inverse
// projections over the map (plus a margin). The inverse transverse Mercator is smooth, so on a
// 128 x 128 table over a city or a country the error stays far below a millimetre, at a
// fraction of the exact cost (which dominated deformation responses). Points off the table
// fall back to the exact inverse.
class FastUnproject {
 public:
  FastUnproject() = default;
  FastUnproject(const MapTransform& transform, XY min, XY max, int cells = 128);
  geo::LonLat operator()(XY p) const;

 private:
  MapTransform transform_;
  XY min_{0, 0};
  double step_x_ = 1, step_y_ = 1;
  int cells_ = 0;
  std::vector<geo::LonLat> table_;  // (cells + 1)^2, row-major
};

struct PlanarNetwork {
  MapTransform transform;
  std::vector<XY> nodes;                                     // by RoadNetwork node index
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;  // by RoadNetwork edge index
  XY min, max;  // extent of the nodes
};

PlanarNetwork make_planar(const model::RoadNetwork& net);

}  // namespace tourmap::deform
