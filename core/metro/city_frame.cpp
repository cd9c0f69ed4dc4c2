#include "metro/city_frame.hpp"

#include "metro/warp.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace tourmap::metro {

ScaleShift fit_scale_translation(const std::vector<XY>& from, const std::vector<XY>& to) {
  std::size_t n = from.size();
  const XY cf = centroid(from, n), ct = centroid(to, n);
  double num = 0, den = 0;
  for (std::size_t i = 0; i < n; ++i) {
    num += (from[i].x - cf.x) * (to[i].x - ct.x) + (from[i].y - cf.y) * (to[i].y - ct.y);
    den += (from[i].x - cf.x) * (from[i].x - cf.x) + (from[i].y - cf.y) * (from[i].y - cf.y);
  }
  double s = den > 0 ? num / den : 1.0;
  return {s, {ct.x - s * cf.x, ct.y - s * cf.y}};
}

CityFrame frame_city(const std::vector<XY>& geo_pos, const Layout& layout, const std::vector<XY>& poi_xy) {
  CityFrame out;
  out.frame = fit_scale_translation(layout.pos, geo_pos);
  for (const auto& p : layout.pos) out.nodes.push_back(out.frame.apply(p));
  // Warp (eq. 5.5, 5.6): stations as control points, geography -> layout.
  Warp warp(geo_pos, out.nodes);
  geo::BBox extent;
  for (const auto& p : geo_pos) extent.extend({p.x, p.y});
  double diag = std::hypot(extent.max_lon - extent.min_lon, extent.max_lat - extent.min_lat);
  double reach = std::max(2000.0, 0.25 * diag);
  for (const auto& p : poi_xy) {
    out.poi_layout.push_back(warp(p));
    double dx = std::max({extent.min_lon - p.x, 0.0, p.x - extent.max_lon});
    double dy = std::max({extent.min_lat - p.y, 0.0, p.y - extent.max_lat});
    out.poi_outside.push_back(std::hypot(dx, dy) > reach);
  }
  // A regular mesh over the network's extent padded by a tenth of its diagonal (Fig. 5.6).
  const int mesh_n = 20;
  out.mesh_side = mesh_n + 1;
  double pad = 0.1 * diag;
  for (int j = 0; j <= mesh_n; ++j)
    for (int i = 0; i <= mesh_n; ++i) {
      XY p{extent.min_lon - pad + (extent.max_lon - extent.min_lon + 2 * pad) * i / mesh_n,
           extent.min_lat - pad + (extent.max_lat - extent.min_lat + 2 * pad) * j / mesh_n};
      out.mesh.geo.push_back(p);
      out.mesh.layout.push_back(warp(p));
    }
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<Kernel::Point_2> pts, hull;
  for (const auto& p : geo_pos) pts.emplace_back(p.x, p.y);
  CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull));
  for (const auto& p : hull) {
    out.outline.geo.push_back({p.x(), p.y()});
    out.outline.layout.push_back(warp({p.x(), p.y()}));
  }
  return out;
}

}  // namespace tourmap::metro
