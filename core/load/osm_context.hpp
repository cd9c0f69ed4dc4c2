#pragma once
// Context layers (model/context.hpp) from an OSM extract (.osm, .osm.gz, .osm.bz2, .osm.pbf)
// through libosmium, in two passes over the file (decompressed once, osm_input.hpp):
//  1. the multipolygon relations of the kinds kept, for libosmium's relations manager;
//  2. nodes and ways: node locations, places, lines (rivers, streams, canals, railways), the
//     coastline, and areas assembled by libosmium's area assembler from closed ways and the
//     multipolygons (one ContextArea per outer ring, its holes with it).
// The sea comes from the coastline (coastline_sea.hpp), closed along the extract's bounds: the
// file header's bounding box, else the box of all node locations.
//
// Tags to kinds (the first that applies):
//   water       natural=water, waterway=riverbank|dock, landuse=reservoir|basin, water=*
//   building    building=* (not "no")
//   park        leisure=park|garden
//   forest      landuse=forest, natural=wood
//   grass       landuse=grass|village_green|recreation_ground, natural=grassland, leisure=pitch
//   farmland    landuse=farmland|meadow|orchard|vineyard
//   residential landuse=residential
//   industrial  landuse=industrial|commercial|retail
//   lines       waterway=river|stream|canal; railway=rail|light_rail|tram|subway|narrow_gauge
//               (not with disused=yes or abandoned=yes); tunnel=* (not "no") marks a tunnel
//   places      nodes with place=city|town|village|suburb|quarter|borough|hamlet|neighbourhood|
//               locality|island|islet and a name (quarter, borough count as suburb, islet as island)
// Names are name=*, UTF-8 as in the data.
//
// Bounded like osm_roads.hpp (max_osm_decompressed_bytes, max_osm_pbf_blobs, max_osm_nodes,
// max_osm_ways), plus max_osm_relations (relations read) and max_context_points (positions
// kept); names are at most max_name_bytes. Beyond a limit: LimitExceeded at once. Polls
// util::check_stop() every 8,192 entities and between buffers. Areas that cannot be assembled
// (broken rings, nodes missing from the extract) and coastline that cannot be closed are counted
// in the stats, not thrown. An extract with none of these yields empty layers, not an error.

#include "load/import_limits.hpp"
#include "model/context.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace tourmap::load {

struct OsmContextStats {
  std::size_t osm_nodes = 0;                                  // nodes read from the file
  std::size_t osm_ways = 0;                                   // ways read from the file
  std::size_t osm_relations = 0;                              // relations read from the file
  std::array<std::size_t, model::kContextAreaKinds> areas{};  // kept, by kind (index: the enum)
  std::array<std::size_t, model::kContextLineKinds> lines{};
  std::array<std::size_t, model::kContextPlaceKinds> places{};
  std::size_t points = 0;                   // positions kept (as max_context_points counts them)
  std::size_t failed_areas = 0;             // closed ways and multipolygons of a kept kind not assembled
  std::size_t incomplete_relations = 0;     // multipolygons of a kept kind with members missing from the file
  std::size_t malformed_tags = 0;           // entities whose tag list is malformed (osm_input.hpp): not assembled
  std::size_t coastline_ways = 0;           // natural=coastline ways (pieces between missing nodes)
  std::size_t coastline_chains = 0;         // after joining them end to end
  std::size_t islands = 0;                  // closed coastline chains with the land inside, within the bounds
  std::size_t sea_rings = 0;                // sea areas made (each an outer ring, islands as its holes)
  std::size_t broken_coastline_chains = 0;  // open chains short of the bounds: no sea from open chains
  std::uint64_t input_bytes = 0;            // OSM data parsed per pass: decompressed XML, or the PBF blobs' raw sizes
};

model::ContextLayers load_osm_context(const std::string& path, OsmContextStats* stats = nullptr,
                                      const ImportLimits& limits = {});

}  // namespace tourmap::load
