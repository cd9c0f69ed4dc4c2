#pragma once
// A road network as a walking graph (issue 17, part 4): the walkable ways' segments as
// undirected edges weighted by their geodesic length in metres, in a Boost.Graph compressed
// sparse row graph (both directions stored), with a kd-tree of the vertices that points snap to.
// Built once per road network version and then only read: safe to share between threads.

#include "geo/nearest_point_tree.hpp"
#include "geo/projection.hpp"
#include "model/road.hpp"

#include <boost/graph/compressed_sparse_row_graph.hpp>

#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

namespace tourmap::walk {

// Whether people walk along an OSM highway class. The road data has no access tags, so this
// goes by class alone: motorways and their links, raceways and bus-only ways are not walked;
// everything else the importer keeps (model/road.hpp: trunk roads too, which mostly have
// pavements in towns) is.
bool is_walkable(std::string_view highway);

struct WalkGraphParams {
  // Vertices of a connected piece with fewer vertices are no snap targets: a point does not
  // start or end its walk on a stray footway fragment cut off by the extract's edge or by
  // missing data, but on the street network around it. 1: every vertex is a target.
  std::size_t min_snap_component = 20;
};

struct WalkEdgeLength {
  double metres = 0;
};

struct WalkGraph {
  using Graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, WalkEdgeLength,
                                                   boost::no_property, std::uint32_t, std::uint32_t>;
  geo::LocalProjection projection;  // for snapping in metres (centred on the network)
  std::vector<geo::LonLat> pos;     // per vertex
  std::vector<std::uint32_t> component;  // per vertex: its connected piece (0 = the largest)
  Graph graph;
  geo::nearest::Tree snap_tree;  // vertices in pieces of at least min_snap_component vertices
  std::size_t walkable_ways = 0, skipped_ways = 0;
  std::size_t snap_vertices = 0;

  std::size_t vertex_count() const { return pos.size(); }
  std::size_t edge_count() const { return boost::num_edges(graph) / 2; }  // undirected
  std::size_t bytes() const;  // approximate memory held (for cache accounting)
};

// Shared: the kd-tree is neither copied nor moved.
std::shared_ptr<const WalkGraph> build_walk_graph(const model::RoadNetwork& net, const WalkGraphParams& params = {});

struct Snap {
  bool found = false;
  std::uint32_t vertex = 0;
  double metres = 0;  // geodesic distance from the point to the vertex
};

// The nearest snap target of `p` (found = false when the graph has none).
Snap snap_to_road(const WalkGraph& g, geo::LonLat p);

}  // namespace tourmap::walk
