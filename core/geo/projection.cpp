#include "geo/projection.hpp"

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/TransverseMercator.hpp>

#include <cstdio>
#include <limits>

namespace tourmap::geo {
namespace {

const GeographicLib::TransverseMercator& tm() {
  // Scale 1 on the central meridian: distances near the city centre are true metres.
  static const GeographicLib::TransverseMercator instance(GeographicLib::Constants::WGS84_a(),
                                                          GeographicLib::Constants::WGS84_f(), 1.0);
  return instance;
}

// Northing of the origin, so that the origin maps to (0, 0). Remembered for the last origin
// per thread: a batch (a 512 x 512 raster's cell centres) projects many points about one
// origin, and this was half of each project() call.
double origin_northing(const LocalProjection& proj) {
  thread_local LonLat last_origin{std::numeric_limits<double>::quiet_NaN(), 0.0};
  thread_local double last_northing = 0.0;
  if (proj.origin.lon == last_origin.lon && proj.origin.lat == last_origin.lat) return last_northing;
  double x = 0.0, y = 0.0;
  tm().Forward(proj.origin.lon, proj.origin.lat, proj.origin.lon, x, y);
  last_origin = proj.origin;
  last_northing = y;
  return y;
}

}  // namespace

LocalProjection projection_for(const BBox& box) {
  if (box.empty()) return LocalProjection{};
  return LocalProjection{box.center()};
}

XY project(const LocalProjection& proj, LonLat p) {
  double x = 0.0, y = 0.0;
  tm().Forward(proj.origin.lon, p.lat, p.lon, x, y);
  return {x, y - origin_northing(proj)};
}

LonLat unproject(const LocalProjection& proj, XY p) {
  double lat = 0.0, lon = 0.0;
  tm().Reverse(proj.origin.lon, p.x, p.y + origin_northing(proj), lat, lon);
  return {lon, lat};
}

double geodesic_distance_m(LonLat a, LonLat b) {
  double s12 = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(a.lat, a.lon, b.lat, b.lon, s12);
  return s12;
}

std::string describe(const LocalProjection& proj) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "tmerc lon0=%.7f lat0=%.7f k0=1", proj.origin.lon, proj.origin.lat);
  return buf;
}

}  // namespace tourmap::geo
