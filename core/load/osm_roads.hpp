#pragma once
// OSM road extracts (.osm, .osm.gz, .osm.bz2, .osm.pbf) through libosmium: every way with a
// highway=* tag that is a road, path or track (not proposed/under construction/an area/a
// platform) becomes a RoadWay; the nodes it uses become RoadNodes. Ways that reference nodes
// missing from the extract are split at the gap.

#include "model/road.hpp"

#include <functional>
#include <string>

namespace tourmap::load {

struct OsmRoadStats {
  std::size_t osm_nodes = 0;      // nodes read from the file
  std::size_t osm_ways = 0;       // ways read from the file
  std::size_t highway_ways = 0;   // ways kept
  std::size_t skipped_ways = 0;   // highway ways left out (class or too few nodes)
  std::size_t missing_nodes = 0;  // way node references without a location in the file
};

// True for the highway=* values tourmap keeps as roads.
bool is_road_class(const char* highway);

model::RoadNetwork load_osm_roads(const std::string& path, OsmRoadStats* stats = nullptr);

}  // namespace tourmap::load
