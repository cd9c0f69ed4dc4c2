#pragma once
// What one import may create, and how much input it may make the loaders read. Imports come
// from the CLI and from authorised HTTP uploads; what they create drives the work of every later
// public read (layouts, clusters, deformations), so the loaders refuse oversized input while
// parsing, at the first record beyond a limit, with a LimitExceeded (load_error.hpp) naming the
// limit. A default-constructed ImportLimits holds the defaults below; the server may pass its own.
//
// The defaults leave ample headroom over the sample data in shared/data (largest sizes in the
// comments) and over real cities and regions, and bound the work of a hostile file. Sizes are
// counts, or bytes where the name ends in _bytes. A value of 0 means "nothing allowed", not
// "unlimited": to lift a limit, set it to a large number.

#include "load/load_error.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tourmap::load {

struct ImportLimits {
  // --- POIs (per city; an import replaces the city's POIs) ---
  // Sample data: 232 (London museums). A city's tourist POIs from OSM (tourism=*, museums,
  // viewpoints, monuments) are some 10^3-10^4 even for Paris or London: 10^5 leaves 10x headroom.
  // Clustering and visual worth grow with this number on every read.
  std::size_t max_pois = 100'000;

  // --- metro networks (line graphs: stations and junctions, edges, lines) ---
  // Sample data: at most 302 nodes, 349 edges (London) and 15 lines (Stuttgart). The largest
  // metro systems have ~500 stations; a LOOM graph of a whole regional rail + tram network a
  // few thousand nodes. The octilinear layout works on these on every uncached read.
  std::size_t max_metro_nodes = 10'000;
  std::size_t max_metro_edges = 20'000;
  // Distinct lines of a network (bus-heavy GTFS line graphs have a few hundred).
  std::size_t max_metro_lines = 1'000;
  // Connection records read before parallel ones are merged into one edge: LOOM LineString
  // features, rows of a connections CSV, stops of a line-ordered CSV. 10x max_metro_edges, so
  // duplicates are merged (not refused) but a file of nothing else cannot run on forever.
  std::size_t max_metro_connections = 200'000;
  // Polyline positions over all edges (sample data: at most 6,590, Stuttgart).
  std::size_t max_metro_geometry_points = 1'000'000;

  // --- OSM road extracts ---
  // Bytes of OSM data after decompression: the XML of a .osm.gz/.osm.bz2 (or the size of a
  // plain .osm), the sum of the blobs' raw sizes of a .osm.pbf. Sample data: at most 14 MB of
  // XML (north-bayreuth). OSM XML compresses 8-15x, so a 64 MiB upload (the server's default
  // body limit) inflates to about 0.5-1 GB; a city-sized region is best imported as PBF,
  // whose raw blobs are ~10x denser than XML. 1 GiB bounds a decompression bomb to ~2 s of
  // CPU and 1 GiB of temporary disk (the decompressed XML is spooled to an unlinked file).
  std::uint64_t max_osm_decompressed_bytes = std::uint64_t{1} << 30;
  // PBF blobs (each holds up to 8,000 entities; sample data: 21, Liechtenstein). Each costs a
  // decode however small it is; 10^5 blobs hold some 10^8 entities, beyond the limits below.
  std::size_t max_osm_pbf_blobs = 100'000;
  // Entities read from the file, kept or not. Their locations are held in memory while the
  // file is read (~16 bytes a node). Sample data: at most 142,832 nodes and 15,247 ways
  // (Liechtenstein); a big city's extract (Berlin) has on the order of 10^7 nodes and 10^6 ways.
  std::size_t max_osm_nodes = 20'000'000;
  std::size_t max_osm_ways = 4'000'000;
  // Relations read from the file (only the context-layer loader reads them: it keeps the
  // multipolygons of the kinds it draws, and their member ways, until they are assembled).
  // Sample data: at most 358 (Liechtenstein); a big city's extract has some 10^5.
  std::size_t max_osm_relations = 1'000'000;
  // Track of the transit routes read from an extract (metro_osm.hpp), counted as work: the
  // routes' way members (one each), the node positions of those ways held while the file is read
  // (8 bytes each), the positions of each route's track assembled from them (a way used by
  // several routes counts for each), and the positions gone over again to repair breaks, place
  // the stations on the track and simplify the edges. Sample data: at most 105,619
  // (Liechtenstein's 16 bus routes, ~7,000 a route). A big city's bus and rail routes (some 10^3
  // relations) ~10^7. At the limit, at most 400 MB of positions are held.
  std::size_t max_osm_track_points = 50'000'000;
  // What the road network keeps (stored, then loaded and deformed by reads). Sample data: at
  // most 54,374 nodes, 4,658 ways and 56,000 edges (Liechtenstein); a big city's roads, paths
  // and tracks are on the order of 10^6 nodes.
  std::size_t max_road_nodes = 5'000'000;
  std::size_t max_road_ways = 1'000'000;
  std::size_t max_road_edges = 6'000'000;
  // Positions the context layers keep (osm_context.hpp: the ring points of areas, the sea's
  // included, line points, one a place; 16 bytes each), stored and drawn under deformed maps.
  // Sample data: at most 76,929 (Liechtenstein, 9,000 buildings); a big city's buildings and
  // land use have on the order of 10^7.
  std::size_t max_context_points = 20'000'000;

  // --- GTFS feeds (metro_gtfs.hpp; the line graph they give is bounded by max_metro_*) ---
  // Bytes of one feed file as read, after decompression from the zip (stop_times.txt of a big
  // city's feed: ~200 MB, at ~58 bytes a row). Bounds a zip bomb, and with max_gtfs_rows the
  // time spent in one file.
  std::uint64_t max_gtfs_file_bytes = std::uint64_t{2} << 30;
  // Records of one feed file, header and blank lines included (~3.5 M stop_times rows in
  // 200 MB). A stop_times row costs ~0.4 us (bench/gtfs_bench: 2.5 M rows/s), so this bounds a
  // file to ~20 s.
  std::size_t max_gtfs_rows = 50'000'000;
  // Rows of stops.txt and trips.txt (and of routes.txt, against max_gtfs_trips: a route needs a
  // trip): each is held while the feed is read (~150 bytes with its id and hash entry). Big city
  // feeds have 10^4-10^5 stops and trips.
  std::size_t max_gtfs_stops = 1'000'000;
  std::size_t max_gtfs_trips = 1'000'000;
  // stop_times rows held at once (8 bytes each): the rows of the trip being read, the stations
  // of the distinct stop patterns, and, when stop_times.txt is not grouped by trip, the rows of
  // the trips spread over the file (a grouped file holds one trip at a time).
  std::size_t max_gtfs_buffered_stop_times = 20'000'000;
  // shapes.txt positions held for the shapes the network uses (24 bytes each); a city's shapes
  // have 10^5-10^6.
  std::size_t max_gtfs_shape_points = 10'000'000;

  // --- text fields (UTF-8 bytes) ---
  // Ids: POI ids, metro node/station ids, line ids and colours. Sample data: at most 15 bytes;
  // GTFS and OSM ids are far shorter than 256.
  std::size_t max_id_bytes = 256;
  // Names, labels, categories, road classes. OSM allows 255 characters a value (at most 1,020
  // bytes of UTF-8; libosmium refuses more than 1,024 bytes); sample data: at most 60 bytes.
  std::size_t max_name_bytes = 1'024;
  // URLs: image, web site, Wikipedia (browsers handle ~2-8 KB; sample data: at most 187).
  std::size_t max_url_bytes = 4'096;

  // --- input formats ---
  // Fields of one CSV row, header included (sample data: at most 22; wide open-data exports
  // have ~100). Bounds the memory of one row whatever the input: a file of commas is one row.
  std::size_t max_csv_fields = 1'000;
  // Bytes of one CSV field (sample data: at most 274). Unused columns are read too, so this is
  // generous enough for a WKT geometry column.
  std::size_t max_csv_field_bytes = 1 << 20;
  // JSON values (numbers, strings, arrays, objects) in one GeoJSON/JSON document, counted
  // while parsing, before the document is whole: it takes some tens of bytes a value. Sample
  // data: at most 26,053 (LOOM Stuttgart). A LOOM network at the metro limits has ~3.5 M (each
  // geometry position is 3), a POI file at max_pois 1-2 M.
  std::size_t max_json_values = 4'000'000;
};

// One limit for listings (413 answers, documentation, configuration by name).
struct ImportLimitInfo {
  std::string_view name;  // the member's name, e.g. "max_pois"; LimitExceeded::limit() uses it
  std::uint64_t value;
  std::string_view unit;  // "count" or "bytes"
};
std::vector<ImportLimitInfo> list_limits(const ImportLimits& limits);
// Sets the limit called `name`; false when there is none.
bool set_limit(ImportLimits& limits, std::string_view name, std::uint64_t value);

// Throws LimitExceeded at `where` when `count` > `limit`: `what` says what was counted
// ("POIs", "bytes of name").
void check_limit(std::uint64_t count, std::uint64_t limit, std::string_view limit_name, const std::string& where,
                 std::string_view what);
// Throws LimitExceeded when `text` is longer than `limit` bytes, naming `field`.
void check_text(std::string_view text, std::size_t limit, std::string_view limit_name, const std::string& where,
                std::string_view field);

}  // namespace tourmap::load
