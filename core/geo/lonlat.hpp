#pragma once
// Geographic coordinates (WGS84 degrees) and bounding boxes: the vocabulary every layer shares.

#include <algorithm>
#include <cmath>
#include <limits>

namespace tourmap::geo {

struct LonLat {
  double lon = 0.0;
  double lat = 0.0;
};

inline bool is_valid(LonLat p) {
  return std::isfinite(p.lon) && std::isfinite(p.lat) && p.lon >= -180.0 && p.lon <= 180.0 &&
         p.lat >= -90.0 && p.lat <= 90.0;
}

// Axis-aligned box in lon/lat. An empty box has min > max until something is added.
struct BBox {
  double min_lon = std::numeric_limits<double>::infinity();
  double min_lat = std::numeric_limits<double>::infinity();
  double max_lon = -std::numeric_limits<double>::infinity();
  double max_lat = -std::numeric_limits<double>::infinity();

  bool empty() const { return min_lon > max_lon || min_lat > max_lat; }
  void extend(LonLat p) {
    min_lon = std::min(min_lon, p.lon);
    min_lat = std::min(min_lat, p.lat);
    max_lon = std::max(max_lon, p.lon);
    max_lat = std::max(max_lat, p.lat);
  }
  bool contains(LonLat p) const {
    return p.lon >= min_lon && p.lon <= max_lon && p.lat >= min_lat && p.lat <= max_lat;
  }
  bool intersects(const BBox& o) const {
    return !(o.min_lon > max_lon || o.max_lon < min_lon || o.min_lat > max_lat ||
             o.max_lat < min_lat);
  }
  LonLat center() const { return {(min_lon + max_lon) / 2.0, (min_lat + max_lat) / 2.0}; }
};

}  // namespace tourmap::geo
