#pragma once
// Shared bookkeeping for the metro loaders: node and line lookup by id, and merging of parallel
// connections (two lines between the same stations become one edge carrying both).

#include "model/metro.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>

namespace tourmap::load {

class MetroBuilder {
 public:
  // Adds a node; throws LoadError at `where` on a duplicate id or invalid coordinates.
  std::uint32_t add_node(model::MetroNode node, const std::string& where);
  // Node index by id; throws LoadError at `where` when unknown.
  std::uint32_t node(const std::string& id, const std::string& where) const;
  bool has_node(const std::string& id) const { return node_index_.count(id) != 0; }
  geo::LonLat pos(std::uint32_t node) const { return net_.nodes.at(node).pos; }
  // Line index by id, adding it the first time.
  std::uint32_t line(const model::MetroLine& line);
  // Adds `line` to the edge between a and b (creating it, straight, if new). Self-loops throw.
  void connect(std::uint32_t a, std::uint32_t b, std::uint32_t line, const std::string& where);
  // Adds an edge with its own geometry (LOOM keeps one feature per edge).
  std::uint32_t add_edge(model::MetroEdge edge, const std::string& where);

  model::MetroNetwork finish(const std::string& source) &&;

 private:
  model::MetroNetwork net_;
  std::unordered_map<std::string, std::uint32_t> node_index_;
  std::unordered_map<std::string, std::uint32_t> line_index_;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge_index_;
};

}  // namespace tourmap::load
