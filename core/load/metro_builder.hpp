#pragma once
// Shared bookkeeping for the metro loaders: node and line lookup by id, merging of parallel
// connections (two lines, or two copies of one edge, between the same stations become one
// edge carrying the union of their lines), and the import limits on what the network holds.

#include "load/import_limits.hpp"
#include "load/metro_load.hpp"
#include "model/metro.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace tourmap::load {

class MetroBuilder {
 public:
  explicit MetroBuilder(const ImportLimits& limits = {}) : limits_(limits) {}

  // Adds a node; throws LoadError at `where` on a duplicate id or invalid coordinates,
  // LimitExceeded beyond max_metro_nodes or on an over-long id or name.
  std::uint32_t add_node(model::MetroNode node, const std::string& where);
  // Node index by id; throws LoadError at `where` when unknown.
  std::uint32_t node(const std::string& id, const std::string& where) const;
  bool has_node(const std::string& id) const { return node_index_.count(id) != 0; }
  geo::LonLat pos(std::uint32_t node) const { return net_.nodes.at(node).pos; }
  // Line index by id, adding it the first time (LimitExceeded beyond max_metro_lines or on an
  // over-long id, label or colour).
  std::uint32_t line(const model::MetroLine& line, const std::string& where = "");
  // Adds `line` to the edge between a and b (creating it, straight, if new). Self-loops throw.
  void connect(std::uint32_t a, std::uint32_t b, std::uint32_t line, const std::string& where);
  // Adds an edge with its own geometry (LOOM keeps one feature per edge). An edge between the
  // same two nodes as an earlier one is merged into it: the earlier edge keeps its geometry
  // and gets the union of the lines. Returns the index of the edge.
  std::uint32_t add_edge(model::MetroEdge edge, const std::string& where);
  // Gives the edge between a and b the track `geometry`, which runs from a to b (it is stored
  // reversed when the edge runs from b to a), if its geometry is still straight (the two points
  // connect() gives it): a loader that learns the track after connecting (metro_osm) keeps the
  // first real geometry. Returns false, changing nothing, when there is no such edge or its
  // geometry has more than two points. Throws LoadError on fewer than two points or invalid
  // coordinates, LimitExceeded beyond max_metro_geometry_points.
  bool replace_straight_geometry(std::uint32_t a, std::uint32_t b, std::vector<geo::LonLat> geometry,
                                 const std::string& where);

  // Connection records seen and how many of them were merged into an existing edge.
  const MetroLoadStats& stats() const { return stats_; }

  model::MetroNetwork finish(const std::string& source) &&;

 private:
  // Counts one connection record (max_metro_connections) and polls check_stop().
  void count_connection(const std::string& where);
  // The edge between a and b, or a new one (max_metro_edges, max_metro_geometry_points).
  std::uint32_t find_edge(std::uint32_t a, std::uint32_t b) const;
  std::uint32_t new_edge(model::MetroEdge edge, const std::string& where);
  void add_line_to_edge(std::uint32_t edge, std::uint32_t line);

  ImportLimits limits_;
  model::MetroNetwork net_;
  MetroLoadStats stats_;
  std::size_t geometry_points_ = 0;
  std::unordered_map<std::string, std::uint32_t> node_index_;
  std::unordered_map<std::string, std::uint32_t> line_index_;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge_index_;
  std::unordered_set<std::uint64_t> edge_lines_;  // (edge << 32 | line) already on the edge
};

}  // namespace tourmap::load
