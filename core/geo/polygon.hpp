#pragma once
// Polygons with holes in lon/lat, and point containment (CGAL's exact predicates, so points on
// or near an edge are classified consistently).

#include "geo/lonlat.hpp"

#include <memory>
#include <vector>

namespace tourmap::geo {

struct Polygon {
  std::vector<LonLat> outer;               // ring without the repeated closing point
  std::vector<std::vector<LonLat>> holes;  // same
};

// A MultiPolygon prepared for many containment queries.
class PolygonSet {
 public:
  explicit PolygonSet(const std::vector<Polygon>& polygons);
  ~PolygonSet();
  PolygonSet(PolygonSet&&) noexcept;
  // Inside (or on the boundary of) any polygon and not strictly inside one of its holes.
  bool contains(LonLat p) const;
  const BBox& bbox() const { return bbox_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  BBox bbox_;
};

// True when the ring is simple (no self-intersections) and has non-zero area.
bool is_simple_ring(const std::vector<LonLat>& ring);

}  // namespace tourmap::geo
