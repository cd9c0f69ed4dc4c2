#pragma once
// A city's local metric projection: transverse Mercator centred on the city (GeographicLib), so
// layout and deformation work in metres with negligible distortion over a city's extent.

#include "geo/lonlat.hpp"

#include <string>

namespace tourmap::geo {

struct XY {
  double x = 0.0;  // metres east of the origin
  double y = 0.0;  // metres north of the origin
};

struct LocalProjection {
  LonLat origin;  // projection centre (central meridian lon0, false northing at lat0)
};

// The projection a city gets: centred on the middle of its bbox.
LocalProjection projection_for(const BBox& box);

XY project(const LocalProjection& proj, LonLat p);
LonLat unproject(const LocalProjection& proj, XY p);

// Geodesic distance in metres on the WGS84 ellipsoid.
double geodesic_distance_m(LonLat a, LonLat b);

// Stable text form stored with a city, e.g. "tmerc lon0=16.37 lat0=48.2".
std::string describe(const LocalProjection& proj);

}  // namespace tourmap::geo
