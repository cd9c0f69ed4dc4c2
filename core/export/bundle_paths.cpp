#include "export/bundle_paths.hpp"

#include <cmath>
#include <map>
#include <optional>

namespace tourmap::map_export {
namespace {

using geo::XY;

constexpr double kMitreLimit = 3;  // a mitre longer than this many offsets is cut (bundles.ts)

std::optional<XY> left_normal(XY a, XY b) {
  const double dx = b.x - a.x, dy = b.y - a.y, length = std::hypot(dx, dy);
  if (length <= 0) return std::nullopt;
  return XY{dy / length, -dx / length};
}

struct End {
  std::uint32_t line;
  XY point;
  XY into;  // the direction of travel at this end, pointing into the node
};

// Where the two ends' lines of travel meet, if near (a corner through the station).
std::optional<XY> meet(const End& a, const End& b) {
  const double det = a.into.x * -b.into.y - a.into.y * -b.into.x;
  if (std::abs(det) < 1e-12) return std::nullopt;
  const double rx = b.point.x - a.point.x, ry = b.point.y - a.point.y;
  const double s = (rx * -b.into.y - ry * -b.into.x) / det;
  const double t = (a.into.x * ry - a.into.y * rx) / det;
  if (s < 0 || t < 0) return std::nullopt;
  const XY p{a.point.x + s * a.into.x, a.point.y + s * a.into.y};
  const double reach = std::hypot(rx, ry);
  if (std::hypot(p.x - a.point.x, p.y - a.point.y) > kMitreLimit * std::max(reach, 1e-9)) return std::nullopt;
  return p;
}

}  // namespace

std::vector<XY> offset_polyline(const std::vector<XY>& points, double offset) {
  if (offset == 0 || points.size() < 2) return points;
  // Each segment's normal; a zero-length segment takes its neighbour's.
  std::vector<std::optional<XY>> normals;
  for (std::size_t i = 1; i < points.size(); ++i) normals.push_back(left_normal(points[i - 1], points[i]));
  for (std::size_t i = 1; i < normals.size(); ++i)
    if (!normals[i]) normals[i] = normals[i - 1];
  for (std::size_t i = normals.size() - 1; i-- > 0;)
    if (!normals[i]) normals[i] = normals[i + 1];
  if (!normals[0]) return points;
  std::vector<XY> out;
  out.reserve(points.size() + 2);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const XY before = *normals[i == 0 ? 0 : i - 1];
    const XY after = *normals[std::min(normals.size() - 1, i)];
    // The mitre: along the mean normal, long enough to keep the offset from both segments.
    const double mx = before.x + after.x, my = before.y + after.y;
    const double m = std::hypot(mx, my) > 0 ? std::hypot(mx, my) : 1;
    const double cos = (mx * after.x + my * after.y) / m;
    const XY p = points[i];
    if (cos > 1 / kMitreLimit) {
      const double length = offset / cos / m;
      out.push_back({p.x + mx * length, p.y + my * length});
    } else {
      out.push_back({p.x + before.x * offset, p.y + before.y * offset});
      out.push_back({p.x + after.x * offset, p.y + after.y * offset});
    }
  }
  return out;
}

LinePieces bundle_pieces(const std::vector<BundleEdge>& edges, std::size_t line_count, double spacing) {
  LinePieces pieces;
  pieces.strokes.resize(line_count);
  pieces.joins.resize(line_count);
  std::map<std::uint32_t, std::vector<End>> ends;  // node -> the pieces' ends there
  for (const auto& edge : edges) {
    if (edge.points.size() < 2) continue;
    const auto n = static_cast<double>(edge.order.size());
    for (std::size_t i = 0; i < edge.order.size(); ++i) {
      const auto line = edge.order[i];
      if (line >= line_count) continue;
      auto polyline = offset_polyline(edge.points, ((n - 1) / 2 - static_cast<double>(i)) * spacing);
      const XY first = polyline.front(), second = polyline[1];
      const XY last = polyline.back(), before_last = polyline[polyline.size() - 2];
      ends[edge.from].push_back({line, first, {first.x - second.x, first.y - second.y}});
      ends[edge.to].push_back({line, last, {last.x - before_last.x, last.y - before_last.y}});
      pieces.strokes[line].push_back(std::move(polyline));
    }
  }
  for (const auto& [node, list] : ends) {
    std::map<std::uint32_t, std::vector<const End*>> by_line;
    for (const auto& end : list) by_line[end.line].push_back(&end);
    for (const auto& [line, two] : by_line) {
      if (two.size() != 2) continue;  // a terminus, or a branch: the station symbol covers it
      const End& a = *two[0];
      const End& b = *two[1];
      if (std::hypot(a.point.x - b.point.x, a.point.y - b.point.y) < spacing * 1e-3) continue;
      if (auto mitre = meet(a, b))
        pieces.joins[line].push_back({a.point, *mitre, b.point});
      else
        pieces.joins[line].push_back({a.point, b.point});
    }
  }
  return pieces;
}

}  // namespace tourmap::map_export
