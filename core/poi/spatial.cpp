#include "poi/spatial.hpp"

#include "geo/nearest_point_tree.hpp"

#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/hilbert_sort.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <tuple>

namespace tourmap::poi {
namespace {

using Kernel = geo::nearest::Kernel;
using Point = geo::nearest::Point;
using PointAndIndex = geo::nearest::PointAndIndex;
using Search = geo::nearest::Search;
using Tree = geo::nearest::Tree;

}  // namespace

Neighbours k_nearest(const std::vector<geo::XY>& points, std::size_t k) {
  Neighbours out;
  const std::size_t n = points.size();
  if (n < 2) return out;
  out.k = std::min(k, n - 1);
  if (out.k == 0) return out;
  out.index.resize(n * out.k);

  std::vector<PointAndIndex> items;
  items.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i) items.emplace_back(Point(points[i].x, points[i].y), i);
  Tree tree(items.begin(), items.end());
  tree.build();

  for (std::uint32_t i = 0; i < n; ++i) {
    // k + 1 neighbours: the point itself is among them unless duplicates crowd it out.
    Search search(tree, Point(points[i].x, points[i].y), static_cast<unsigned>(out.k + 1));
    std::uint32_t* row = &out.index[i * out.k];
    std::size_t filled = 0;
    for (auto it = search.begin(); it != search.end() && filled < out.k; ++it) {
      std::uint32_t j = std::get<1>(it->first);
      if (j != i) row[filled++] = j;
    }
  }
  return out;
}

std::vector<std::uint32_t> hilbert_order(const std::vector<geo::XY>& points) {
  std::vector<Point> cgal_points;
  cgal_points.reserve(points.size());
  for (const auto& p : points) cgal_points.emplace_back(p.x, p.y);
  // The adapter sorts keys of the property map's own key type (std::size_t).
  std::vector<std::size_t> keys(points.size());
  for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = i;
  using SortTraits = CGAL::Spatial_sort_traits_adapter_2<Kernel, CGAL::Pointer_property_map<Point>::type>;
  CGAL::hilbert_sort(keys.begin(), keys.end(), SortTraits(CGAL::make_property_map(cgal_points)));
  return std::vector<std::uint32_t>(keys.begin(), keys.end());
}

}  // namespace tourmap::poi
