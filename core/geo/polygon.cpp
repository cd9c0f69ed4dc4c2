#include "geo/polygon.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

namespace tourmap::geo {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
using Ring = std::vector<Point>;

Ring to_ring(const std::vector<LonLat>& ring) {
  Ring pts;
  pts.reserve(ring.size());
  for (const auto& p : ring) pts.emplace_back(p.lon, p.lat);
  return pts;
}

bool in_ring(const Ring& ring, const Point& p) {
  return ring.size() >= 3 &&
         CGAL::bounded_side_2(ring.begin(), ring.end(), p, Kernel()) != CGAL::ON_UNBOUNDED_SIDE;
}

bool strictly_in_ring(const Ring& ring, const Point& p) {
  return ring.size() >= 3 && CGAL::bounded_side_2(ring.begin(), ring.end(), p, Kernel()) == CGAL::ON_BOUNDED_SIDE;
}

}  // namespace

struct PolygonSet::Impl {
  struct Prepared {
    Ring outer;
    std::vector<Ring> holes;
    BBox box;
  };
  std::vector<Prepared> polygons;
};

PolygonSet::PolygonSet(const std::vector<Polygon>& polygons) : impl_(std::make_unique<Impl>()) {
  for (const auto& poly : polygons) {
    Impl::Prepared prepared{to_ring(poly.outer), {}, {}};
    for (const auto& hole : poly.holes) prepared.holes.push_back(to_ring(hole));
    for (const auto& p : poly.outer) {
      prepared.box.extend(p);
      bbox_.extend(p);
    }
    impl_->polygons.push_back(std::move(prepared));
  }
}

PolygonSet::~PolygonSet() = default;
PolygonSet::PolygonSet(PolygonSet&&) noexcept = default;

bool PolygonSet::contains(LonLat p) const {
  if (!bbox_.contains(p)) return false;
  Point q(p.lon, p.lat);
  for (const auto& poly : impl_->polygons) {
    if (!poly.box.contains(p) || !in_ring(poly.outer, q)) continue;
    bool in_hole = false;
    for (const auto& hole : poly.holes) in_hole = in_hole || strictly_in_ring(hole, q);
    if (!in_hole) return true;
  }
  return false;
}

bool is_simple_ring(const std::vector<LonLat>& ring) {
  if (ring.size() < 3) return false;
  auto pts = to_ring(ring);
  return CGAL::is_simple_2(pts.begin(), pts.end(), Kernel()) &&
         CGAL::polygon_area_2(pts.begin(), pts.end(), Kernel()) != 0.0;
}

}  // namespace tourmap::geo
