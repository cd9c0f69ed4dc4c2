#include "load/metro_builder.hpp"

#include "load/load_error.hpp"
#include "util/stop.hpp"

#include <algorithm>

namespace tourmap::load {
namespace {

constexpr std::uint32_t kNoEdge = static_cast<std::uint32_t>(-1);

}  // namespace

std::uint32_t MetroBuilder::add_node(model::MetroNode node, const std::string& where) {
  if (node.id.empty()) throw LoadError(where, "node without an id");
  check_text(node.id, limits_.max_id_bytes, "max_id_bytes", where, "node id");
  check_text(node.station_id, limits_.max_id_bytes, "max_id_bytes", where, "station id");
  check_text(node.name, limits_.max_name_bytes, "max_name_bytes", where, "station name");
  if (!geo::is_valid(node.pos)) throw LoadError(where, "invalid coordinates for node '" + node.id + "'");
  check_limit(net_.nodes.size() + 1, limits_.max_metro_nodes, "max_metro_nodes", where, "nodes (stations and junctions)");
  if ((net_.nodes.size() & 1023) == 0) util::check_stop();
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

std::uint32_t MetroBuilder::line(const model::MetroLine& line, const std::string& where) {
  if (auto it = line_index_.find(line.id); it != line_index_.end()) return it->second;
  check_text(line.id, limits_.max_id_bytes, "max_id_bytes", where, "line id");
  check_text(line.label, limits_.max_name_bytes, "max_name_bytes", where, "line label");
  check_text(line.color, limits_.max_id_bytes, "max_id_bytes", where, "line colour");
  check_limit(net_.lines.size() + 1, limits_.max_metro_lines, "max_metro_lines", where, "lines");
  auto index = static_cast<std::uint32_t>(net_.lines.size());
  line_index_.emplace(line.id, index);
  net_.lines.push_back(line);
  return index;
}

void MetroBuilder::count_connection(const std::string& where) {
  ++stats_.connections;
  check_limit(stats_.connections, limits_.max_metro_connections, "max_metro_connections", where,
              "connections (edge records, parallel ones included)");
  if ((stats_.connections & 1023) == 1) util::check_stop();
}

std::uint32_t MetroBuilder::find_edge(std::uint32_t a, std::uint32_t b) const {
  auto it = edge_index_.find(std::minmax(a, b));
  return it == edge_index_.end() ? kNoEdge : it->second;
}

std::uint32_t MetroBuilder::new_edge(model::MetroEdge edge, const std::string& where) {
  check_limit(net_.edges.size() + 1, limits_.max_metro_edges, "max_metro_edges", where, "edges");
  geometry_points_ += edge.geometry.size();
  check_limit(geometry_points_, limits_.max_metro_geometry_points, "max_metro_geometry_points", where,
              "edge geometry positions");
  auto index = static_cast<std::uint32_t>(net_.edges.size());
  edge_index_.emplace(std::minmax(edge.from, edge.to), index);
  std::vector<std::uint32_t> lines = std::move(edge.lines);
  edge.lines.clear();
  net_.edges.push_back(std::move(edge));
  for (auto l : lines) add_line_to_edge(index, l);
  return index;
}

void MetroBuilder::add_line_to_edge(std::uint32_t edge, std::uint32_t line) {
  if (edge_lines_.insert(std::uint64_t{edge} << 32 | line).second) net_.edges[edge].lines.push_back(line);
}

void MetroBuilder::connect(std::uint32_t a, std::uint32_t b, std::uint32_t line, const std::string& where) {
  if (a == b) throw LoadError(where, "edge from node '" + net_.nodes[a].id + "' to itself");
  count_connection(where);
  auto index = find_edge(a, b);
  if (index == kNoEdge) {
    model::MetroEdge edge;
    edge.from = a;
    edge.to = b;
    edge.geometry = {net_.nodes[a].pos, net_.nodes[b].pos};
    index = new_edge(std::move(edge), where);
  } else {
    ++stats_.merged_connections;
  }
  add_line_to_edge(index, line);
}

std::uint32_t MetroBuilder::add_edge(model::MetroEdge edge, const std::string& where) {
  if (edge.from == edge.to) throw LoadError(where, "edge from node '" + net_.nodes[edge.from].id + "' to itself");
  count_connection(where);
  for (const auto& p : edge.geometry)
    if (!geo::is_valid(p)) throw LoadError(where, "invalid coordinates in edge geometry");
  auto index = find_edge(edge.from, edge.to);
  if (index == kNoEdge) return new_edge(std::move(edge), where);
  // A parallel edge: the first one's geometry stays, the lines are merged.
  ++stats_.merged_connections;
  for (auto l : edge.lines) add_line_to_edge(index, l);
  return index;
}

bool MetroBuilder::replace_straight_geometry(std::uint32_t a, std::uint32_t b, std::vector<geo::LonLat> geometry,
                                             const std::string& where) {
  if (geometry.size() < 2) throw LoadError(where, "edge geometry of fewer than two points");
  for (const auto& p : geometry)
    if (!geo::is_valid(p)) throw LoadError(where, "invalid coordinates in edge geometry");
  const auto index = find_edge(a, b);
  if (index == kNoEdge || net_.edges[index].geometry.size() > 2) return false;
  auto& edge = net_.edges[index];
  geometry_points_ += geometry.size() - edge.geometry.size();
  check_limit(geometry_points_, limits_.max_metro_geometry_points, "max_metro_geometry_points", where,
              "edge geometry positions");
  if (edge.from != a) std::reverse(geometry.begin(), geometry.end());
  edge.geometry = std::move(geometry);
  return true;
}

model::MetroNetwork MetroBuilder::finish(const std::string& source) && {
  if (net_.station_count() == 0) throw LoadError(source, "no stations");
  return std::move(net_);
}

}  // namespace tourmap::load
