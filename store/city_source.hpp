#pragma once
// A whole city from open data in one import (issue 16, part 4): from an OSM extract its
// transit network (route relations, load/metro_osm.hpp; or a GTFS feed when one is given,
// load/metro_gtfs.hpp), its POIs (load/osm_pois.hpp), and its road network with the context
// layers (load/osm_roads.hpp, load/osm_context.hpp; stored as the road network of the city's
// id). Everything is loaded first, outside any transaction, then written in one transaction:
// a source that fails to load or to store changes nothing. The same files and modes twice
// change nothing (unless forced).
//
// Long imports report their stages through `progress` (the CLI prints them, the HTTP upload
// publishes them on WS /api/v1/events). Bounded by the import limits like every import.

#include "importer.hpp"

#include <functional>
#include <string>
#include <vector>

namespace tourmap::store {

struct ImportProgress {
  std::string city;   // the city id
  std::string stage;  // "transit" | "pois" | "roads" | "context" | "writing" | "done"
  int step = 0;       // 1-based index of the stage
  int steps = 0;      // stages in all
  std::string detail;  // what the stage before it read, e.g. "5 lines, 38 stations"
};

struct CitySourceImport {
  CityMeta city;                     // id, name; attribution of the transit data: default OpenStreetMap's, or "GTFS feed <file>"
  std::string osm;                   // the extract (.osm, .osm.gz, .osm.bz2, .osm.pbf)
  std::string gtfs;                  // optional: a GTFS feed (zip or folder) for the transit network
  std::string osm_attribution;       // of the extract's POIs and roads; default OpenStreetMap's
  std::vector<std::string> modes;    // transit modes (load/metro_osm.hpp); none: the rail modes present, else bus
  bool force = false;
  std::function<void(const ImportProgress&)> progress{};  // called on the importing thread
};

// The import's results: transit ("metro"), "pois" and "roads", in that order. All three are
// skipped together when the source is unchanged.
std::vector<ImportResult> import_city_source(Db& db, const CitySourceImport& request,
                                             const load::ImportLimits& limits = {});

// The source version of such an import: the files' fingerprint, the modes and the processing.
inline constexpr const char* kCitySourceProcessing = "city-source/1";
std::string city_source_fingerprint(const CitySourceImport& request);

}  // namespace tourmap::store
