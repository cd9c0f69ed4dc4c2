#include "walk/walk_graph.hpp"

#include <boost/pending/disjoint_sets.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

namespace tourmap::walk {

bool is_walkable(std::string_view highway) {
  static constexpr std::array<std::string_view, 6> kNotWalked = {"motorway", "motorway_link", "raceway",
                                                                 "bus_guideway", "busway", "escape"};
  return std::find(kNotWalked.begin(), kNotWalked.end(), highway) == kNotWalked.end();
}

std::size_t WalkGraph::bytes() const {
  const std::size_t edges = boost::num_edges(graph);
  return sizeof(WalkGraph) + pos.capacity() * sizeof(geo::LonLat) + component.capacity() * sizeof(std::uint32_t) +
         (pos.size() + 1) * sizeof(std::uint32_t) + edges * (sizeof(std::uint32_t) + sizeof(WalkEdgeLength)) +
         snap_vertices * 64;  // kd-tree: the point tuple and its share of the nodes
}

std::shared_ptr<const WalkGraph> build_walk_graph(const model::RoadNetwork& net, const WalkGraphParams& params) {
  auto out = std::make_shared<WalkGraph>();
  WalkGraph& g = *out;
  constexpr auto kNone = std::numeric_limits<std::uint32_t>::max();
  // Road nodes on walkable ways only, numbered in order of first use.
  std::vector<std::uint32_t> vertex_of(net.nodes.size(), kNone);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> arcs;
  std::vector<WalkEdgeLength> lengths;
  const auto vertex = [&](std::uint32_t node) {
    if (vertex_of[node] == kNone) {
      vertex_of[node] = static_cast<std::uint32_t>(g.pos.size());
      g.pos.push_back(net.nodes[node].pos);
    }
    return vertex_of[node];
  };
  for (const auto& way : net.ways) {
    if (!is_walkable(way.highway)) {
      ++g.skipped_ways;
      continue;
    }
    ++g.walkable_ways;
    for (std::size_t i = 1; i < way.nodes.size(); ++i) {
      const auto a = way.nodes[i - 1], b = way.nodes[i];
      if (a == b || a >= net.nodes.size() || b >= net.nodes.size()) continue;
      const auto u = vertex(a), v = vertex(b);
      const double m = geo::geodesic_distance_m(net.nodes[a].pos, net.nodes[b].pos);
      arcs.emplace_back(u, v);
      arcs.emplace_back(v, u);
      lengths.push_back({m});
      lengths.push_back({m});
    }
  }
  const auto n = static_cast<std::uint32_t>(g.pos.size());
  g.graph = WalkGraph::Graph(boost::edges_are_unsorted_multi_pass, arcs.begin(), arcs.end(), lengths.begin(), n);

  // Connected pieces (union-find over the segments), numbered by size: 0 is the largest.
  // Iterator property maps, not raw pointers: the CSR graph's detail::get hides the global
  // pointer overloads from the disjoint sets' unqualified calls.
  std::vector<std::uint32_t> rank(n, 0), parent(n);
  const auto index = boost::typed_identity_property_map<std::uint32_t>();
  boost::disjoint_sets sets(boost::make_iterator_property_map(rank.begin(), index),
                            boost::make_iterator_property_map(parent.begin(), index));
  for (std::uint32_t v = 0; v < n; ++v) sets.make_set(v);
  for (std::size_t i = 0; i < arcs.size(); i += 2) sets.union_set(arcs[i].first, arcs[i].second);
  std::vector<std::uint32_t> size(n, 0);
  for (std::uint32_t v = 0; v < n; ++v) ++size[sets.find_set(v)];
  std::vector<std::uint32_t> roots;
  for (std::uint32_t v = 0; v < n; ++v)
    if (size[v] > 0) roots.push_back(v);
  std::stable_sort(roots.begin(), roots.end(), [&](auto a, auto b) { return size[a] > size[b]; });
  std::vector<std::uint32_t> piece_of_root(n, 0);
  for (std::uint32_t i = 0; i < roots.size(); ++i) piece_of_root[roots[i]] = i;
  g.component.resize(n);
  g.projection = geo::projection_for(model::bbox_of(net));
  for (std::uint32_t v = 0; v < n; ++v) {
    const auto root = static_cast<std::uint32_t>(sets.find_set(v));
    g.component[v] = piece_of_root[root];
    if (size[root] < params.min_snap_component) continue;
    const auto xy = geo::project(g.projection, g.pos[v]);
    g.snap_tree.insert({geo::nearest::Point(xy.x, xy.y), v});
    ++g.snap_vertices;
  }
  // Now, not lazily at the first search: searches may run in parallel. Not when empty: CGAL's
  // build dereferences the first point (UBSan); snap_to_road never searches an empty tree.
  if (g.snap_vertices > 0) g.snap_tree.build();
  return out;
}

Snap snap_to_road(const WalkGraph& g, geo::LonLat p) {
  Snap s;
  if (g.snap_vertices == 0) return s;
  const auto xy = geo::project(g.projection, p);
  geo::nearest::Search search(g.snap_tree, geo::nearest::Point(xy.x, xy.y), 1);
  const auto it = search.begin();
  if (it == search.end()) return s;
  s.found = true;
  s.vertex = std::get<1>(it->first);
  s.metres = geo::geodesic_distance_m(p, g.pos[s.vertex]);
  return s;
}

}  // namespace tourmap::walk
