#include "load/metro_builder.hpp"

#include "load/load_error.hpp"

#include <algorithm>

namespace tourmap::load {

std::uint32_t MetroBuilder::add_node(model::MetroNode node, const std::string& where) {
  if (node.id.empty()) throw LoadError(where, "node without an id");
  if (!geo::is_valid(node.pos)) throw LoadError(where, "invalid coordinates for node '" + node.id + "'");
  auto index = static_cast<std::uint32_t>(net_.nodes.size());
  if (!node_index_.emplace(node.id, index).second)
    throw LoadError(where, "duplicate node id '" + node.id + "'");
  net_.nodes.push_back(std::move(node));
  return index;
}

std::uint32_t MetroBuilder::node(const std::string& id, const std::string& where) const {
  auto it = node_index_.find(id);
  if (it == node_index_.end()) throw LoadError(where, "unknown station or node '" + id + "'");
  return it->second;
}

std::uint32_t MetroBuilder::line(const model::MetroLine& line) {
  auto [it, inserted] = line_index_.emplace(line.id, static_cast<std::uint32_t>(net_.lines.size()));
  if (inserted) net_.lines.push_back(line);
  return it->second;
}

void MetroBuilder::connect(std::uint32_t a, std::uint32_t b, std::uint32_t line, const std::string& where) {
  if (a == b) throw LoadError(where, "edge from node '" + net_.nodes[a].id + "' to itself");
  auto key = std::minmax(a, b);
  auto it = edge_index_.find(key);
  if (it == edge_index_.end()) {
    model::MetroEdge edge;
    edge.from = a;
    edge.to = b;
    edge.geometry = {net_.nodes[a].pos, net_.nodes[b].pos};
    it = edge_index_.emplace(key, static_cast<std::uint32_t>(net_.edges.size())).first;
    net_.edges.push_back(std::move(edge));
  }
  auto& lines = net_.edges[it->second].lines;
  if (std::find(lines.begin(), lines.end(), line) == lines.end()) lines.push_back(line);
}

std::uint32_t MetroBuilder::add_edge(model::MetroEdge edge, const std::string& where) {
  if (edge.from == edge.to) throw LoadError(where, "edge from node '" + net_.nodes[edge.from].id + "' to itself");
  for (const auto& p : edge.geometry)
    if (!geo::is_valid(p)) throw LoadError(where, "invalid coordinates in edge geometry");
  auto index = static_cast<std::uint32_t>(net_.edges.size());
  edge_index_.emplace(std::minmax(edge.from, edge.to), index);
  net_.edges.push_back(std::move(edge));
  return index;
}

model::MetroNetwork MetroBuilder::finish(const std::string& source) && {
  if (net_.station_count() == 0) throw LoadError(source, "no stations");
  return std::move(net_);
}

}  // namespace tourmap::load
