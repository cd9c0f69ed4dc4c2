#include "metro/octilinear_shapes.hpp"

#include <algorithm>
#include <cmath>

// std::hypot is exact but slow; these lengths are sums of a few hundred segments.
namespace {
inline double length(double dx, double dy) { return std::sqrt(dx * dx + dy * dy); }
}  // namespace

namespace tourmap::metro {

int octant_of(XY v, double eps) {
  const double ax = std::abs(v.x), ay = std::abs(v.y);
  if (ax <= eps && ay <= eps) return -1;
  if (ay <= eps) return v.x > 0 ? 0 : 4;
  if (ax <= eps) return v.y > 0 ? 2 : 6;
  if (std::abs(ax - ay) > eps) return -1;
  if (v.x > 0) return v.y > 0 ? 1 : 7;
  return v.y > 0 ? 3 : 5;
}

std::vector<OctilinearShape> octilinear_shapes(XY p, XY q, double eps) {
  const XY v{q.x - p.x, q.y - p.y};
  if (octant_of(v, eps) >= 0) return {OctilinearShape{{p, q}, 0, 0}};
  std::vector<OctilinearShape> shapes;
  for (int i = 0; i < 8; ++i)
    for (int step = 1; step <= 3; ++step) {
      const int j = (i + step) % 8;
      const XY di = kOctants[i], dj = kOctants[j];
      // v = a * di + b * dj (Cramer's rule); both must be positive.
      const double det = di.x * dj.y - di.y * dj.x;
      const double a = (v.x * dj.y - v.y * dj.x) / det, b = (di.x * v.y - di.y * v.x) / det;
      if (a <= eps || b <= eps) continue;
      shapes.push_back({{p, {p.x + a * di.x, p.y + a * di.y}, q}, 1, step});
      shapes.push_back({{p, {p.x + b * dj.x, p.y + b * dj.y}, q}, 1, step});
      if (step == 1) {
        // The symmetric Z: half of one leg, the other leg, the second half.
        const XY c1{p.x + a / 2 * di.x, p.y + a / 2 * di.y};
        shapes.push_back({{p, c1, {c1.x + b * dj.x, c1.y + b * dj.y}, q}, 2, 2});
        const XY c2{p.x + b / 2 * dj.x, p.y + b / 2 * dj.y};
        shapes.push_back({{p, c2, {c2.x + a * di.x, c2.y + a * di.y}, q}, 2, 2});
      }
    }
  return shapes;
}

double polyline_length(const std::vector<XY>& pts) {
  double s = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) s += length(pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y);
  return s;
}

int polyline_bends(const std::vector<XY>& pts, double min_turn_rad) {
  int bends = 0;
  bool have = false;
  double last = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const double dx = pts[i].x - pts[i - 1].x, dy = pts[i].y - pts[i - 1].y;
    if (dx == 0 && dy == 0) continue;
    const double a = std::atan2(dy, dx);
    if (have) {
      double turn = std::abs(std::remainder(a - last, 2 * M_PI));
      if (turn > min_turn_rad) ++bends;
    }
    last = a;
    have = true;
  }
  return bends;
}

std::vector<XY> simplify_polyline(const std::vector<XY>& pts, double eps) {
  std::vector<XY> out;
  for (const auto& p : pts) {
    if (!out.empty() && std::abs(out.back().x - p.x) <= eps && std::abs(out.back().y - p.y) <= eps) continue;
    if (out.size() >= 2) {
      const XY a = out[out.size() - 2], b = out.back();
      const double cross = (b.x - a.x) * (p.y - b.y) - (b.y - a.y) * (p.x - b.x);
      const double dot = (b.x - a.x) * (p.x - b.x) + (b.y - a.y) * (p.y - b.y);
      const double len = length(b.x - a.x, b.y - a.y) + length(p.x - b.x, p.y - b.y);
      if (std::abs(cross) <= eps * len && dot > 0) out.back() = p;  // b lies on the straight run a..p
      else out.push_back(p);
    } else {
      out.push_back(p);
    }
  }
  if (out.size() == 1 && pts.size() >= 2) out.push_back(pts.back());
  return out;
}

XY point_at_length(const std::vector<XY>& pts, double s) {
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const double len = length(pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y);
    if (s <= len && len > 0) {
      const double t = s / len;
      return {pts[i - 1].x + t * (pts[i].x - pts[i - 1].x), pts[i - 1].y + t * (pts[i].y - pts[i - 1].y)};
    }
    s -= len;
  }
  return pts.back();
}

std::vector<XY> points_at_lengths(const std::vector<XY>& pts, const std::vector<double>& arcs) {
  std::vector<XY> out;
  if (arcs.size() < 3) return out;
  out.reserve(arcs.size() - 2);
  std::size_t seg = 1;
  double seg_start = 0, seg_len = pts.size() > 1 ? length(pts[1].x - pts[0].x, pts[1].y - pts[0].y) : 0;
  for (std::size_t k = 1; k + 1 < arcs.size(); ++k) {
    const double s = arcs[k];
    while (seg + 1 < pts.size() && s > seg_start + seg_len) {
      seg_start += seg_len;
      ++seg;
      seg_len = length(pts[seg].x - pts[seg - 1].x, pts[seg].y - pts[seg - 1].y);
    }
    const double t = seg_len > 0 ? std::clamp((s - seg_start) / seg_len, 0.0, 1.0) : 0.0;
    out.push_back({pts[seg - 1].x + t * (pts[seg].x - pts[seg - 1].x), pts[seg - 1].y + t * (pts[seg].y - pts[seg - 1].y)});
  }
  return out;
}

std::vector<XY> polyline_between(const std::vector<XY>& pts, double s0, double s1) {
  std::vector<XY> out{point_at_length(pts, s0)};
  double at = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    at += length(pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y);
    if (at > s0 && at < s1) out.push_back(pts[i]);
  }
  out.push_back(point_at_length(pts, s1));
  return out;
}

}  // namespace tourmap::metro
