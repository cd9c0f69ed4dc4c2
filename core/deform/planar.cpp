#include "deform/planar.hpp"

#include <algorithm>

namespace tourmap::deform {

XY MapTransform::to_map(geo::LonLat p) const {
  auto m = geo::project(projection, p);
  return {(m.x - center.x) / metres_per_unit, (m.y - center.y) / metres_per_unit};
}

geo::LonLat MapTransform::to_lonlat(XY p) const {
  return geo::unproject(projection, {p.x * metres_per_unit + center.x, p.y * metres_per_unit + center.y});
}

FastUnproject::FastUnproject(const MapTransform& transform, XY min, XY max, int cells)
    : transform_(transform), min_(min), cells_(cells) {
  step_x_ = std::max(max.x - min.x, 1e-9) / cells;
  step_y_ = std::max(max.y - min.y, 1e-9) / cells;
  table_.reserve(static_cast<std::size_t>(cells + 1) * (cells + 1));
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) table_.push_back(transform.to_lonlat({min.x + i * step_x_, min.y + j * step_y_}));
}

geo::LonLat FastUnproject::operator()(XY p) const {
  double fx = (p.x - min_.x) / step_x_, fy = (p.y - min_.y) / step_y_;
  if (!(fx >= 0 && fy >= 0 && fx <= cells_ && fy <= cells_)) return transform_.to_lonlat(p);
  int i = std::min(static_cast<int>(fx), cells_ - 1), j = std::min(static_cast<int>(fy), cells_ - 1);
  double u = fx - i, v = fy - j;
  const auto& a = table_[static_cast<std::size_t>(j) * (cells_ + 1) + i];
  const auto& b = table_[static_cast<std::size_t>(j) * (cells_ + 1) + i + 1];
  const auto& c = table_[static_cast<std::size_t>(j + 1) * (cells_ + 1) + i + 1];
  const auto& d = table_[static_cast<std::size_t>(j + 1) * (cells_ + 1) + i];
  double w0 = (1 - u) * (1 - v), w1 = u * (1 - v), w2 = u * v, w3 = (1 - u) * v;
  return {w0 * a.lon + w1 * b.lon + w2 * c.lon + w3 * d.lon, w0 * a.lat + w1 * b.lat + w2 * c.lat + w3 * d.lat};
}

PlanarNetwork make_planar(const model::RoadNetwork& net) {
  PlanarNetwork out;
  auto box = model::bbox_of(net);
  out.transform.projection = geo::projection_for(box);
  std::vector<XY> metres;
  metres.reserve(net.nodes.size());
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  for (std::size_t i = 0; i < net.nodes.size(); ++i) {
    auto m = geo::project(out.transform.projection, net.nodes[i].pos);
    metres.push_back(m);
    if (i == 0) {
      x0 = x1 = m.x;
      y0 = y1 = m.y;
    }
    x0 = std::min(x0, m.x);
    x1 = std::max(x1, m.x);
    y0 = std::min(y0, m.y);
    y1 = std::max(y1, m.y);
  }
  out.transform.center = {(x0 + x1) / 2, (y0 + y1) / 2};
  out.transform.metres_per_unit = std::max({x1 - x0, y1 - y0, 1e-6}) / kMapUnits;
  out.nodes.reserve(metres.size());
  for (const auto& m : metres)
    out.nodes.push_back({(m.x - out.transform.center.x) / out.transform.metres_per_unit,
                         (m.y - out.transform.center.y) / out.transform.metres_per_unit});
  out.min = {(x0 - out.transform.center.x) / out.transform.metres_per_unit,
             (y0 - out.transform.center.y) / out.transform.metres_per_unit};
  out.max = {(x1 - out.transform.center.x) / out.transform.metres_per_unit,
             (y1 - out.transform.center.y) / out.transform.metres_per_unit};
  out.edges.reserve(net.edges.size());
  for (const auto& e : net.edges) out.edges.emplace_back(e.from, e.to);
  return out;
}

}  // namespace tourmap::deform
