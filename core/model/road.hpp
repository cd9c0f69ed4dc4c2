#pragma once
// A road network as a graph: OSM nodes used by highway ways, and the segments between
// consecutive nodes of a way. Ways keep their node sequence so they can be drawn as polylines.

#include "geo/projection.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace tourmap::model {

struct RoadNode {
  std::int64_t osm_id = 0;
  geo::LonLat pos;
};

struct RoadWay {
  std::int64_t osm_id = 0;
  std::string highway;  // OSM highway=* value: the road class
  std::string name;
  std::vector<std::uint32_t> nodes;  // indices into RoadNetwork::nodes, >= 2
};

struct RoadEdge {
  std::uint32_t from = 0;  // index into RoadNetwork::nodes
  std::uint32_t to = 0;
  std::uint32_t way = 0;   // index into RoadNetwork::ways
};

struct RoadNetwork {
  std::vector<RoadNode> nodes;
  std::vector<RoadWay> ways;
  std::vector<RoadEdge> edges;
};

struct RoadNetworkInfo {
  std::string id;  // url-safe slug, e.g. "monaco"
  std::string name;
  geo::BBox bbox;
  geo::LocalProjection projection;
  std::string attribution;
  std::int64_t version = 0;  // changes with every import of the network
  std::size_t node_count = 0;
  std::size_t way_count = 0;
  std::size_t edge_count = 0;
};

// Edges are the consecutive node pairs of every way, in way order.
std::vector<RoadEdge> edges_of(const std::vector<RoadWay>& ways);
geo::BBox bbox_of(const RoadNetwork& net);

}  // namespace tourmap::model
