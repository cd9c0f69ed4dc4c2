#include "model/metro.hpp"
#include "model/poi.hpp"
#include "model/road.hpp"

namespace tourmap::model {

geo::BBox bbox_of(const MetroNetwork& net) {
  geo::BBox box;
  for (const auto& node : net.nodes) box.extend(node.pos);
  for (const auto& edge : net.edges)
    for (const auto& p : edge.geometry) box.extend(p);
  return box;
}

geo::BBox bbox_of(const std::vector<Poi>& pois) {
  geo::BBox box;
  for (const auto& poi : pois) box.extend(poi.pos);
  return box;
}

std::vector<RoadEdge> edges_of(const std::vector<RoadWay>& ways) {
  std::vector<RoadEdge> edges;
  for (std::uint32_t w = 0; w < ways.size(); ++w) {
    const auto& nodes = ways[w].nodes;
    for (std::size_t i = 1; i < nodes.size(); ++i) edges.push_back({nodes[i - 1], nodes[i], w});
  }
  return edges;
}

geo::BBox bbox_of(const RoadNetwork& net) {
  geo::BBox box;
  for (const auto& node : net.nodes) box.extend(node.pos);
  return box;
}

}  // namespace tourmap::model
