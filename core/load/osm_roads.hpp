#pragma once
// OSM road extracts (.osm, .osm.gz, .osm.bz2, .osm.pbf) through libosmium: every way with a
// highway=* tag that is a road, path or track (not proposed/under construction/an area/a
// platform) becomes a RoadWay; the nodes it uses become RoadNodes. Ways that reference nodes
// missing from the extract are split at the gap.
//
// Bounded: a .gz/.bz2 is decompressed (at most ImportLimits::max_osm_decompressed_bytes) into
// an unlinked temporary file before libosmium parses it; a PBF's blobs are counted and their
// decompressed sizes summed before it is decoded; nodes, ways and what the road network keeps
// are counted while reading. Beyond a limit: LimitExceeded (a LoadError) at once. Polls
// util::check_stop() every 1 MiB of decompressed data and every 8,192 entities, and lets
// util::Stopped through unchanged; nothing stays behind (no file, no descriptor).

#include "load/import_limits.hpp"
#include "model/road.hpp"

#include <cstdint>
#include <functional>
#include <string>

namespace tourmap::load {

struct OsmRoadStats {
  std::size_t osm_nodes = 0;      // nodes read from the file
  std::size_t osm_ways = 0;       // ways read from the file
  std::size_t highway_ways = 0;   // ways kept
  std::size_t skipped_ways = 0;   // highway ways left out (class or too few nodes)
  std::size_t missing_nodes = 0;  // way node references without a location in the file
  std::uint64_t input_bytes = 0;  // OSM data parsed: decompressed XML, or the PBF blobs' raw sizes
};

// True for the highway=* values tourmap keeps as roads.
bool is_road_class(const char* highway);

model::RoadNetwork load_osm_roads(const std::string& path, OsmRoadStats* stats = nullptr,
                                  const ImportLimits& limits = {});

}  // namespace tourmap::load
