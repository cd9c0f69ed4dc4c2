#pragma once
// A data manifest: which files under a data directory become which cities and road networks.
// scripts/sample-data.json describes ../shared/data; `tourmap import manifest` runs one.
//
// {"cities": [{"id": "vienna", "name": "Vienna",
//              "metro": {"format": "loom", "files": ["metro/loom_wien.json"], "attribution": "...",
//                        "rules": {"strip_suffixes": [" (Wien)"], ...}},
//              "pois": {"file": "poi/x.json", "category": "sight", "attribution": "..."}}],
//              {"id": "monaco", "name": "Monaco",
//               "source": {"osm": "roads/monaco.osm.gz", "gtfs": "...", "modes": ["bus"], "attribution": "..."}}],
//  "roads": [{"id": "krems", "name": "Krems", "file": "roads/krems.osm.gz", "attribution": "..."}]}
//
// "rules" (optional) clean the city's names and lines at import: store/metro_rules.hpp. A city
// with a "source" instead of "metro" and "pois" is imported whole from open data
// (store/city_source.hpp: transit, POIs, and the road network of its id with the context).

#include "city_source.hpp"
#include "importer.hpp"

#include <functional>
#include <string>
#include <vector>

namespace tourmap::store {

struct Manifest {
  std::vector<MetroImport> metros;
  std::vector<PoiImport> pois;
  std::vector<RoadImport> roads;
  std::vector<CitySourceImport> sources;
};

// Parses the manifest text; relative file paths are resolved against `data_dir`.
// Throws std::invalid_argument naming the entry and field on a malformed manifest.
Manifest parse_manifest(const std::string& json_text, const std::string& data_dir);

// Runs every import (each in its own transaction), calling `progress` after each. Throws on the
// first failure; imports done before it stay.
std::vector<ImportResult> run_manifest(Db& db, const Manifest& manifest, bool force,
                                       const std::function<void(const ImportResult&)>& progress,
                                       const load::ImportLimits& limits = {});

}  // namespace tourmap::store
