#pragma once
// Points of interest from an OSM extract (.osm, .osm.gz, .osm.bz2, .osm.pbf) through libosmium
// (issue 16, part 3), one pass over its nodes and ways (decompressed and bounded by
// osm_input.hpp). Kept, with a name:
//   tourism   attraction, museum, gallery, viewpoint, zoo, theme_park, aquarium
//   historic  any value but "no" and "yes" (castle, monument, memorial, ruins, church, ...)
//   amenity   theatre, arts_centre; place_of_worship only with wikidata or wikipedia
// from nodes (their location) and from ways (the mean of their distinct node locations, for
// areas such as a museum's building). Relations (a castle mapped as a multipolygon) are not
// read: they are counted in the stats.
//
// Category: the first of tourism, historic, amenity kept, as a word ("theme park", "place of
// worship"). Links: website (website, contact:website, url), wikipedia ("de:Vaduz" becomes
// https://de.wikipedia.org/wiki/Vaduz), else wikidata (https://www.wikidata.org/wiki/Q..),
// image (an http(s) image tag, else wikimedia_commons "File:..." through Commons' FilePath).
// Popularity, a proxy for how well known a place is (visual worth ranks POIs by it, 5.4.1):
// 2 for a wikidata item, 2 for a Wikipedia article, 1 for a heritage listing (2 at a national
// level, heritage=1 or 2), and by category: 1 for museum, castle, zoo, theme park, aquarium,
// attraction, 0.5 for the rest.
//
// A way and a node, or two ways, of the same name (case-insensitive) within 200 m, or with
// the same wikidata item within 1 km, are one place: kept once, at the node's position (the
// label point mappers chose) or the first way's, with the links either has. Ids are "n<osm
// id>" or "w<osm id>".
//
// Bounded like osm_roads.hpp (max_osm_decompressed_bytes, max_osm_pbf_blobs, max_osm_nodes,
// max_osm_ways), max_pois for the places kept, max_name_bytes and max_url_bytes for their
// texts (a longer name or link is an error, not truncated). Polls util::check_stop().

#include "load/import_limits.hpp"
#include "model/poi.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace tourmap::load {

struct OsmPoiStats {
  std::size_t osm_nodes = 0;          // nodes read
  std::size_t osm_ways = 0;           // ways read
  std::size_t from_nodes = 0;         // places kept from nodes
  std::size_t from_ways = 0;          // places kept from ways
  std::size_t merged = 0;             // way places merged into a place found before them
  std::size_t relations_skipped = 0;  // relations with tags of a kept kind (not read)
  std::size_t unnamed = 0;            // entities of a kept kind without a name
  std::size_t no_location = 0;        // ways whose nodes are all outside the extract
  std::size_t malformed_tags = 0;     // entities with a malformed tag list (osm_input.hpp)
};

std::vector<model::Poi> load_osm_pois(const std::string& path, OsmPoiStats* stats = nullptr,
                                      const ImportLimits& limits = {});

// True for the file names load_osm_pois reads (.osm, .osm.gz, .osm.bz2, .osm.pbf, .pbf).
bool is_osm_file_name(const std::string& name);

}  // namespace tourmap::load
