#pragma once
// Small exact-enough predicates on segments for the layout post-passes: how two segments touch
// (not, at a point, or along a stretch) and point-to-segment distance. `eps` is an absolute
// tolerance in layout units (layouts use units of about an edge length / 10).

#include "metro/layout_graph.hpp"

#include <algorithm>
#include <cmath>

namespace tourmap::metro {

struct SegmentContact {
  enum Kind { none, point, overlap } kind = none;
  XY at{0, 0};  // for `point`
};

inline double point_segment_distance2(XY p, XY a, XY b) {
  const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double ex = p.x - (a.x + t * dx), ey = p.y - (a.y + t * dy);
  return ex * ex + ey * ey;
}

inline double point_segment_distance(XY p, XY a, XY b) { return std::sqrt(point_segment_distance2(p, a, b)); }

inline SegmentContact segment_contact(XY p1, XY p2, XY q1, XY q2, double eps) {
  if (std::max(p1.x, p2.x) + eps < std::min(q1.x, q2.x) || std::max(q1.x, q2.x) + eps < std::min(p1.x, p2.x) ||
      std::max(p1.y, p2.y) + eps < std::min(q1.y, q2.y) || std::max(q1.y, q2.y) + eps < std::min(p1.y, p2.y))
    return {};
  const auto side = [eps](XY a, XY b, XY c) {
    const double cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    const double len = std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y));  // not hypot: hot, and slow
    return std::abs(cross) <= eps * std::max(len, eps) ? 0 : (cross > 0 ? 1 : -1);
  };
  const int o1 = side(p1, p2, q1), o2 = side(p1, p2, q2), o3 = side(q1, q2, p1), o4 = side(q1, q2, p2);
  if (o1 == 0 && o2 == 0) {  // collinear: compare along the longer axis
    const bool use_x = std::abs(p2.x - p1.x) + std::abs(q2.x - q1.x) >= std::abs(p2.y - p1.y) + std::abs(q2.y - q1.y);
    const auto key = [use_x](XY p) { return use_x ? p.x : p.y; };
    const double lo = std::max(std::min(key(p1), key(p2)), std::min(key(q1), key(q2)));
    const double hi = std::min(std::max(key(p1), key(p2)), std::max(key(q1), key(q2)));
    if (hi - lo > eps) return {SegmentContact::overlap, {}};
    if (hi - lo < -eps) return {};
    for (XY c : {q1, q2})
      if (point_segment_distance(c, p1, p2) <= eps) return {SegmentContact::point, c};
    for (XY c : {p1, p2})
      if (point_segment_distance(c, q1, q2) <= eps) return {SegmentContact::point, c};
    return {};
  }
  if (o1 * o2 > 0 || o3 * o4 > 0) return {};
  // They meet: where (the touching end point, or the crossing point).
  if (o1 == 0) return {SegmentContact::point, q1};
  if (o2 == 0) return {SegmentContact::point, q2};
  if (o3 == 0) return {SegmentContact::point, p1};
  if (o4 == 0) return {SegmentContact::point, p2};
  const double dx = p2.x - p1.x, dy = p2.y - p1.y, ex = q2.x - q1.x, ey = q2.y - q1.y;
  const double t = ((q1.x - p1.x) * ey - (q1.y - p1.y) * ex) / (dx * ey - dy * ex);
  return {SegmentContact::point, {p1.x + t * dx, p1.y + t * dy}};
}

}  // namespace tourmap::metro
