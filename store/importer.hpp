#pragma once
// Imports: load a source with the core loaders, then write it in one transaction. A file that
// fails to load or to store changes nothing. Re-importing unchanged files is a no-op unless forced
// (or the target was deleted since). The loaders enforce `limits` (load/import_limits.hpp):
// beyond one they throw load::LimitExceeded, a load::LoadError; they poll util::check_stop(),
// whose util::Stopped passes through unchanged.

#include "repo.hpp"

#include "load/import_limits.hpp"
#include "load/metro_load.hpp"
#include "load/name_rules.hpp"

#include <functional>
#include <string>
#include <vector>

namespace tourmap::store {

enum class MetroFormat { loom, station_csvs, line_csv, osm, gtfs };
// "loom" | "station-csvs" | "line-csv" | "osm" | "gtfs"; throws std::invalid_argument otherwise.
MetroFormat parse_metro_format(const std::string& name);

struct ImportResult {
  std::string kind;    // "metro" | "pois" | "roads"
  std::string target;  // city or road network id
  bool skipped = false;  // same files as the last import: nothing written
  std::int64_t version = 0;
  std::size_t rows = 0;   // rows written (nodes + edges + lines, POIs, or nodes + ways + edges)
  double seconds = 0.0;
  std::string summary;  // e.g. "98 stations, 105 edges, 5 lines"
  std::vector<std::string> warnings;  // what the source had wrong and the import worked around
                                      // (OSM: one per route relation with a problem)
};

struct MetroImport {
  CityMeta city;
  MetroFormat format = MetroFormat::loom;
  std::vector<std::string> files;  // loom/line-csv/osm/gtfs: 1 file (gtfs: a zip or a folder); station-csvs: stations, lines, connections
  bool force = false;
  load::MetroRules rules{};  // applied after loading (load/name_rules.hpp)
  std::vector<std::string> modes{};  // osm, gtfs: the transit modes (load/metro_osm.hpp); none: the rail modes present, else bus
};
// The network in the request's files, as its format reads them (no rules applied); `summary`
// gets what an OSM import read ("; OSM train: 4 routes ...").
model::MetroNetwork load_metro_files(const MetroImport& request, const load::ImportLimits& limits = {},
                                     load::MetroLoadStats* stats = nullptr, std::string* summary = nullptr,
                                     std::vector<std::string>* warnings = nullptr);
// Loads the files, applies the rules, styles lines of close colours (metro/line_styles.hpp)
// and stores the result. Skipped when the files, the rules and the import-time processing are
// those of the last import (metro_fingerprint).
ImportResult import_metro(Db& db, const MetroImport& request, const load::ImportLimits& limits = {});

// The loading half of the imports, for imports that write several things in one transaction
// (store/city_source.hpp): what is stored, the rows it makes and a summary of what was read.
struct LoadedMetro {
  model::MetroNetwork net;  // rules applied, lines styled
  std::size_t rows = 0;
  std::string summary;
  std::vector<std::string> warnings;
};
LoadedMetro load_metro_for_import(const MetroImport& request, const load::ImportLimits& limits = {});
struct LoadedRoads {
  model::RoadNetwork net;
  model::ContextLayers context;
  std::size_t rows = 0;
  std::string summary;
};
LoadedRoads load_roads_for_import(const std::string& file, const load::ImportLimits& limits = {});
// Throws std::invalid_argument naming the first POI far outside the network (a wrong file).
void check_pois_near_city(const model::MetroNetwork& net, const std::string& city_id,
                          const std::vector<model::Poi>& pois, const std::string& source);

struct PoiImport {
  std::string city_id;
  std::string file;
  std::string default_category;
  std::string attribution;
  bool force = false;
};
ImportResult import_pois(Db& db, const PoiImport& request, const load::ImportLimits& limits = {});

struct RoadImport {
  RoadMeta network;
  std::string file;
  bool force = false;
};
// The roads and the context layers of one extract (load/osm_context.hpp), in one transaction.
ImportResult import_roads(Db& db, const RoadImport& request, const load::ImportLimits& limits = {});

// A road import's source version: the file's fingerprint and the processing at import
// (kRoadProcessing): a build that reads more of the extract (the context layers came with
// "roads+context/1") imports it again; the same file twice changes nothing.
inline constexpr const char* kRoadProcessing = "roads+context/1";

// FNV-1a 64 over the files' bytes, as hex: identifies a source version.
std::string fingerprint_files(const std::vector<std::string>& files);

// A metro import's source version: the files' fingerprint, then one of the rules (their
// canonical JSON) and of the processing at import (kMetroProcessing). A changed rule, or a
// build that cleans or styles differently, imports the city again; the same files and rules
// twice change nothing.
inline constexpr const char* kMetroProcessing = "names+styles+colours/2";
std::string metro_fingerprint(const std::vector<std::string>& files, const load::MetroRules& rules);

}  // namespace tourmap::store
