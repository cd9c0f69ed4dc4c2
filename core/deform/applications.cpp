#include "deform/applications.hpp"

#include "deform/system.hpp"
#include "geo/polygon.hpp"
#include "util/stop.hpp"

#include "geo/nearest_point_tree.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace tourmap::deform {
namespace {

double dist(XY a, XY b) { return std::hypot(a.x - b.x, a.y - b.y); }

double point_segment_distance(XY p, XY a, XY b) {
  double dx = b.x - a.x, dy = b.y - a.y;
  double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return dist(p, {a.x + t * dx, a.y + t * dy});
}

void douglas_peucker(const std::vector<XY>& line, std::size_t first, std::size_t last, double tol,
                     std::vector<bool>& keep) {
  double worst = -1;
  std::size_t at = first;
  for (std::size_t i = first + 1; i < last; ++i) {
    double d = point_segment_distance(line[i], line[first], line[last]);
    if (d > worst) {
      worst = d;
      at = i;
    }
  }
  if (worst > tol) {
    keep[at] = true;
    douglas_peucker(line, first, at, tol, keep);
    douglas_peucker(line, at, last, tol, keep);
  }
}

// Point at fraction t of a polyline's length.
XY point_at(const std::vector<XY>& line, const std::vector<double>& cumulative, double t) {
  double want = t * cumulative.back();
  auto it = std::lower_bound(cumulative.begin(), cumulative.end(), want);
  std::size_t i = std::clamp<std::size_t>(static_cast<std::size_t>(it - cumulative.begin()), 1, line.size() - 1);
  double seg = cumulative[i] - cumulative[i - 1];
  double f = seg > 0 ? (want - cumulative[i - 1]) / seg : 0.0;
  return {line[i - 1].x + f * (line[i].x - line[i - 1].x), line[i - 1].y + f * (line[i].y - line[i - 1].y)};
}

std::vector<double> cumulative_length(const std::vector<XY>& line) {
  std::vector<double> c(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i) c[i] = c[i - 1] + dist(line[i - 1], line[i]);
  return c;
}

}  // namespace

std::vector<double> focus_edge_scales(const PlanarNetwork& net, const std::vector<FocusRegion>& regions) {
  std::vector<double> scales(net.edges.size(), 1.0);
  std::vector<std::unique_ptr<geo::PolygonSet>> polygons;
  for (const auto& r : regions) {
    if (r.polygon.empty()) {
      polygons.push_back(nullptr);
      continue;
    }
    geo::Polygon poly;
    for (const auto& p : r.polygon) poly.outer.push_back({p.x, p.y});  // planar coordinates in LonLat fields
    polygons.push_back(std::make_unique<geo::PolygonSet>(std::vector<geo::Polygon>{poly}));
  }
  for (std::size_t i = 0; i < net.edges.size(); ++i) {
    if ((i & 4095) == 0) util::check_stop();
    const auto& a = net.nodes[net.edges[i].first];
    const auto& b = net.nodes[net.edges[i].second];
    XY mid{(a.x + b.x) / 2, (a.y + b.y) / 2};
    for (std::size_t r = 0; r < regions.size(); ++r) {
      if (regions[r].scale <= scales[i]) continue;  // cannot raise this edge's scale
      bool inside = false;
      if (polygons[r]) {
        // The bbox first: the exact test walks the polygon's edges.
        const auto& box = polygons[r]->bbox();
        inside = mid.x >= box.min_lon && mid.x <= box.max_lon && mid.y >= box.min_lat && mid.y <= box.max_lat &&
                 polygons[r]->contains({mid.x, mid.y});
      } else {
        inside = dist(mid, regions[r].center) <= regions[r].radius;
      }
      if (inside) scales[i] = regions[r].scale;
    }
  }
  return scales;
}

struct NodeIndex::Impl {
  using Point = geo::nearest::Point;
  using Search = geo::nearest::Search;
  geo::nearest::Tree tree;
};

NodeIndex::NodeIndex(const std::vector<XY>& nodes) : impl_(std::make_unique<Impl>()) {
  for (std::uint32_t i = 0; i < nodes.size(); ++i) impl_->tree.insert({Impl::Point(nodes[i].x, nodes[i].y), i});
  impl_->tree.build();
}

NodeIndex::~NodeIndex() = default;

std::uint32_t NodeIndex::nearest(XY p) const {
  Impl::Search search(impl_->tree, Impl::Point(p.x, p.y), 1);
  return std::get<1>(search.begin()->first);
}

std::vector<XY> simplify_polyline(const std::vector<XY>& line, double tolerance) {
  if (line.size() <= 2 || tolerance <= 0) return line;
  std::vector<bool> keep(line.size(), false);
  keep.front() = keep.back() = true;
  douglas_peucker(line, 0, line.size() - 1, tolerance, keep);
  std::vector<XY> out;
  for (std::size_t i = 0; i < line.size(); ++i)
    if (keep[i]) out.push_back(line[i]);
  return out;
}

std::vector<Guide> route_to_sketch(const PlanarNetwork& net, const std::vector<std::uint32_t>& route,
                                   const std::vector<XY>& sketch) {
  std::vector<XY> path;
  for (auto n : route) path.push_back(net.nodes[n]);
  auto along_route = cumulative_length(path);
  auto along_sketch = cumulative_length(sketch);
  std::vector<Guide> guides;
  for (std::size_t i = 0; i < route.size(); ++i) {
    double t = along_route.back() > 0 ? along_route[i] / along_route.back()
                                      : (route.size() > 1 ? double(i) / double(route.size() - 1) : 0.0);
    guides.push_back({route[i], point_at(sketch, along_sketch, t)});
  }
  return guides;
}

std::vector<Guide> sorted_guides(std::vector<Guide> guides) {
  std::stable_sort(guides.begin(), guides.end(), [](const Guide& a, const Guide& b) { return a.node < b.node; });
  std::vector<Guide> out;
  for (const auto& g : guides) {
    if (!out.empty() && out.back().node == g.node) out.back() = g;  // the later one wins
    else out.push_back(g);
  }
  return out;
}

std::vector<std::uint32_t> guide_nodes(const std::vector<Guide>& sorted) {
  std::vector<std::uint32_t> out;
  out.reserve(sorted.size());
  for (const auto& g : sorted) out.push_back(g.node);
  return out;
}

std::vector<XY> map_points(const Prepared& p, const std::vector<XY>& deformed_points,
                           const std::vector<XY>& deformed_nodes, const std::vector<XY>& rest_nodes,
                           const NodeIndex& index, const std::vector<XY>& queries) {
  std::vector<XY> out;
  out.reserve(queries.size());
  for (const auto& q : queries) {
    if (p.grid) {
      out.push_back(grid::place(*p.grid, deformed_points, grid::embed(*p.grid, q)));
    } else {
      auto n = index.nearest(q);
      out.push_back({q.x + deformed_nodes[n].x - rest_nodes[n].x, q.y + deformed_nodes[n].y - rest_nodes[n].y});
    }
  }
  return out;
}

}  // namespace tourmap::deform
