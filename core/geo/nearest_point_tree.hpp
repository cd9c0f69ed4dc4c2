#pragma once
// The kd-tree over plane points with an index each (CGAL's k-neighbour search), as the
// nearest-station, nearest-node and POI lookups use it: insert (Point, index) tuples, search
// with a Search over the Tree.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_2.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/property_map.h>

#include <cstdint>
#include <tuple>

namespace tourmap::geo::nearest {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
using PointAndIndex = std::tuple<Point, std::uint32_t>;
using Traits = CGAL::Search_traits_adapter<PointAndIndex, CGAL::Nth_of_tuple_property_map<0, PointAndIndex>,
                                           CGAL::Search_traits_2<Kernel>>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
using Tree = Search::Tree;

}  // namespace tourmap::geo::nearest
