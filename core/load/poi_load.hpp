#pragma once
// POI loaders: GeoJSON (Point features), CSV, and a JSON/JS array of objects. Field names vary by
// source, so each field is looked up under the names the known sources use (case-insensitive):
//   name: name, title;  position: lon/lng/longitude + lat/latitude (or the GeoJSON geometry);
//   category: category, type, Wikipedia_Type, tourism;  image: image, image_url, thumbnail;
//   url: url, website, weitere_inf;  wikipedia: wikipedia, wikipedia url, wikidata;
//   rank: rank;  popularity: popularity, score;  id: feature id, id, objectid.
// A record without a name or a valid position is an error naming the record. Beyond
// limits.max_pois records, or with a text field longer than its limit (max_name_bytes for the
// name and category, max_id_bytes for the id, max_url_bytes for the URLs), the load stops with
// LimitExceeded naming the record and the field: nothing is truncated. Polls util::check_stop().

#include "load/import_limits.hpp"
#include "model/poi.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace tourmap::load {

struct PoiLoadOptions {
  std::string default_category;  // used when the source has no category field
};

std::vector<model::Poi> parse_pois_geojson(std::string_view text, const std::string& source,
                                           const PoiLoadOptions& options = {}, const ImportLimits& limits = {});
std::vector<model::Poi> parse_pois_csv(std::string_view text, const std::string& source,
                                       const PoiLoadOptions& options = {}, const ImportLimits& limits = {});
// A JSON array of objects, optionally wrapped as a JS statement `var name = [...];`.
std::vector<model::Poi> parse_pois_js_array(std::string_view text, const std::string& source,
                                            const PoiLoadOptions& options = {}, const ImportLimits& limits = {});

// Picks the parser from the content (and the file extension for CSV); an OSM extract (.osm,
// .osm.gz, .osm.bz2, .osm.pbf) gives its tourist places (load/osm_pois.hpp).
std::vector<model::Poi> load_pois(const std::string& path, const PoiLoadOptions& options = {}, const ImportLimits& limits = {});

}  // namespace tourmap::load
