#include "load/poi_load.hpp"

#include "load/csv.hpp"
#include "load/file.hpp"
#include "load/json_fields.hpp"
#include "load/load_error.hpp"
#include "load/osm_pois.hpp"
#include "load/text_repair.hpp"
#include "util/stop.hpp"

#include <unordered_set>

namespace tourmap::load {
namespace {

constexpr std::string_view kName[] = {"name", "title"};
constexpr std::string_view kLon[] = {"lon", "lng", "longitude", "long"};
constexpr std::string_view kLat[] = {"lat", "latitude"};
constexpr std::string_view kCategory[] = {"category", "wikipedia_type", "tourism", "type"};
constexpr std::string_view kImage[] = {"image", "image_url", "thumbnail", "img"};
constexpr std::string_view kUrl[] = {"url", "website", "weitere_inf", "homepage"};
constexpr std::string_view kWikipedia[] = {"wikipedia", "wikipedia url", "wikipedia_url",
                                                                "wikidata"};
constexpr std::string_view kRank[] = {"rank"};
constexpr std::string_view kPopularity[] = {"popularity", "score"};
constexpr std::string_view kId[] = {"id", "objectid", "osm_id"};

// Before a record is read: at most limits.max_pois records, and a stop check now and then.
void next_poi(std::size_t count_so_far, const std::string& where, const ImportLimits& limits) {
  check_limit(count_so_far + 1, limits.max_pois, "max_pois", where, "POIs");
  if ((count_so_far & 1023) == 0) util::check_stop();
}

// Repairs double-encoded text, refusing it when longer than `limit` bytes (mojibake takes at
// most 3 bytes per byte, so longer raw text is refused before it is looked at).
std::string repaired_text(const std::string& raw, std::size_t limit, std::string_view limit_name,
                          const std::string& where, std::string_view field) {
  if (raw.size() / 3 > limit) check_text(raw, limit, limit_name, where, field);  // too long even once repaired
  auto text = repair_mojibake(raw);
  check_text(text, limit, limit_name, where, field);
  return text;
}

// Checks the record and gives it a unique id.
void finish_poi(model::Poi& poi, const std::string& where, std::unordered_set<std::string>& ids,
                const PoiLoadOptions& options, const ImportLimits& limits) {
  poi.name = repaired_text(poi.name, limits.max_name_bytes, "max_name_bytes", where, "name");
  if (poi.name.empty()) throw LoadError(where, "POI without a name");
  if (!geo::is_valid(poi.pos)) throw LoadError(where, "POI '" + poi.name + "' has invalid coordinates");
  if (poi.category.empty()) poi.category = options.default_category;
  poi.category = repaired_text(poi.category, limits.max_name_bytes, "max_name_bytes", where, "category");
  check_text(poi.id, limits.max_id_bytes, "max_id_bytes", where, "id");
  check_text(poi.image_url, limits.max_url_bytes, "max_url_bytes", where, "image URL");
  check_text(poi.url, limits.max_url_bytes, "max_url_bytes", where, "URL");
  check_text(poi.wikipedia, limits.max_url_bytes, "max_url_bytes", where, "wikipedia");
  if (!ids.insert(poi.id).second) throw LoadError(where, "duplicate POI id '" + poi.id + "'");
}

// Fills the non-position fields from a JSON object (GeoJSON properties or a plain record).
void fill_from_object(model::Poi& poi, const nlohmann::json& obj) {
  poi.name = json_text_any(obj, kName).value_or("");
  poi.category = json_text_any(obj, kCategory).value_or("");
  poi.image_url = json_text_any(obj, kImage).value_or("");
  poi.url = json_text_any(obj, kUrl).value_or("");
  poi.wikipedia = json_text_any(obj, kWikipedia).value_or("");
  poi.rank = json_number_any(obj, kRank);
  poi.popularity = json_number_any(obj, kPopularity);
}

std::vector<model::Poi> parse_object_array(const nlohmann::json& arr, const std::string& source,
                                           const PoiLoadOptions& options, const ImportLimits& limits) {
  std::vector<model::Poi> pois;
  std::unordered_set<std::string> ids;
  for (std::size_t i = 0; i < arr.size(); ++i) {
    auto where = source + " record " + std::to_string(i);
    next_poi(pois.size(), where, limits);
    const auto& obj = arr[i];
    if (!obj.is_object()) throw LoadError(where, "expected an object");
    model::Poi poi;
    fill_from_object(poi, obj);
    auto lon = json_number_any(obj, kLon), lat = json_number_any(obj, kLat);
    if (!lon || !lat) throw LoadError(where, "missing lon/lat");
    poi.pos = {*lon, *lat};
    poi.id = json_text_any(obj, kId).value_or(std::to_string(i));
    finish_poi(poi, where, ids, options, limits);
    pois.push_back(std::move(poi));
  }
  return pois;
}

}  // namespace

std::vector<model::Poi> parse_pois_geojson(std::string_view text, const std::string& source,
                                           const PoiLoadOptions& options, const ImportLimits& limits) {
  auto doc = parse_json(text, source, limits);
  if (!doc.is_object() || json_text(doc, "type").value_or("") != "FeatureCollection" ||
      !doc.contains("features") || !doc["features"].is_array())
    throw LoadError(source, "expected a GeoJSON FeatureCollection with a 'features' array");
  std::vector<model::Poi> pois;
  std::unordered_set<std::string> ids;
  const auto& features = doc["features"];
  for (std::size_t i = 0; i < features.size(); ++i) {
    auto where = source + " feature " + std::to_string(i);
    next_poi(pois.size(), where, limits);
    const auto& f = features[i];
    if (!f.is_object() || !f.contains("geometry") || !f["geometry"].is_object())
      throw LoadError(where, "feature without a geometry");
    const auto& geom = f["geometry"];
    if (json_text(geom, "type").value_or("") != "Point") throw LoadError(where, "POI geometry must be a Point");
    const auto& c = geom.value("coordinates", nlohmann::json());
    if (!c.is_array() || c.size() < 2 || !c[0].is_number() || !c[1].is_number())
      throw LoadError(where, "coordinates must be [lon, lat]");
    model::Poi poi;
    const auto props = f.value("properties", nlohmann::json::object());
    fill_from_object(poi, props);
    poi.pos = {c[0].get<double>(), c[1].get<double>()};
    poi.id = json_text(f, "id").value_or(json_text_any(props, kId).value_or(std::to_string(i)));
    finish_poi(poi, where, ids, options, limits);
    pois.push_back(std::move(poi));
  }
  return pois;
}

std::vector<model::Poi> parse_pois_csv(std::string_view text, const std::string& source,
                                       const PoiLoadOptions& options, const ImportLimits& limits) {
  CsvReader table(text, source, limits);
  auto c_name = table.column(kName);
  auto c_lon = table.column(kLon);
  auto c_lat = table.column(kLat);
  auto c_category = table.find_column(kCategory);
  auto c_image = table.find_column(kImage);
  auto c_url = table.find_column(kUrl);
  auto c_wiki = table.find_column(kWikipedia);
  auto c_rank = table.find_column(kRank);
  auto c_pop = table.find_column(kPopularity);
  auto c_id = table.find_column(kId);

  auto text_at = [](const std::vector<std::string>& row, std::optional<std::size_t> c) {
    return c && !is_null_field(row[*c]) ? row[*c] : std::string();
  };
  std::vector<model::Poi> pois;
  std::unordered_set<std::string> ids;
  while (table.next()) {
    const auto& row = table.row();
    auto where = table.where();
    next_poi(pois.size(), where, limits);
    model::Poi poi;
    poi.name = row[c_name];
    poi.pos = {parse_number(row[c_lon], where, "longitude"), parse_number(row[c_lat], where, "latitude")};
    poi.category = text_at(row, c_category);
    poi.image_url = text_at(row, c_image);
    poi.url = text_at(row, c_url);
    // Some sources list several URLs in one field: keep the first.
    if (auto comma = poi.url.find(", "); comma != std::string::npos) poi.url.resize(comma);
    poi.wikipedia = text_at(row, c_wiki);
    if (c_rank && !is_null_field(row[*c_rank])) poi.rank = parse_number(row[*c_rank], where, "rank");
    if (c_pop && !is_null_field(row[*c_pop])) poi.popularity = parse_number(row[*c_pop], where, "popularity");
    // Without an id column the data line number is the stable id.
    poi.id = c_id && !is_null_field(row[*c_id]) ? row[*c_id] : std::string("L").append(std::to_string(table.line()));
    finish_poi(poi, where, ids, options, limits);
    pois.push_back(std::move(poi));
  }
  return pois;
}

std::vector<model::Poi> parse_pois_js_array(std::string_view text, const std::string& source,
                                            const PoiLoadOptions& options, const ImportLimits& limits) {
  // Strip a `var name =` prefix and a trailing `;` so the rest is a JSON array.
  auto open = text.find('[');
  auto close = text.rfind(']');
  if (open == std::string_view::npos || close == std::string_view::npos || close < open)
    throw LoadError(source, "expected a JSON array of POI objects");
  auto doc = parse_json(text.substr(open, close - open + 1), source, limits);
  return parse_object_array(doc, source, options, limits);
}

std::vector<model::Poi> load_pois(const std::string& path, const PoiLoadOptions& options, const ImportLimits& limits) {
  auto name = file_name(path);
  if (is_osm_file_name(name)) return load_osm_pois(path, nullptr, limits);
  auto text = read_file(path);
  auto ends_with = [&](std::string_view suffix) {
    return name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (ends_with(".csv")) return parse_pois_csv(text, name, options, limits);
  auto first = text.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
  if (first != std::string::npos && text[first] == '{') return parse_pois_geojson(text, name, options, limits);
  if (first != std::string::npos && (text[first] == '[' || ends_with(".js")))
    return parse_pois_js_array(text, name, options, limits);
  throw LoadError(name, "unknown POI format (expected GeoJSON, CSV or a JSON/JS array)");
}

}  // namespace tourmap::load
