#include "manifest.hpp"

#include "metro_rules.hpp"

#include <nlohmann/json.hpp>

#include <stdexcept>

namespace tourmap::store {
namespace {

std::string str(const nlohmann::json& obj, const char* key, const std::string& where, bool required = true) {
  if (obj.contains(key) && obj[key].is_string()) return obj[key].get<std::string>();
  if (required) throw std::invalid_argument(where + ": missing string field '" + key + "'");
  return "";
}

std::string resolve(const std::string& data_dir, const std::string& file) {
  if (!file.empty() && file[0] == '/') return file;
  return data_dir + "/" + file;
}

std::vector<std::string> modes(const nlohmann::json& obj, const std::string& where) {
  std::vector<std::string> out;
  if (!obj.contains("modes")) return out;
  if (!obj["modes"].is_array()) throw std::invalid_argument(where + ".modes: expected an array of strings");
  for (const auto& mode : obj["modes"]) {
    if (!mode.is_string()) throw std::invalid_argument(where + ".modes: expected strings");
    out.push_back(mode.get<std::string>());
  }
  return out;
}

// {"id", "name", "source": {"osm", "gtfs"?, "modes"?, "attribution"?}}
CitySourceImport parse_source(const nlohmann::json& c, const std::string& where, const std::string& data_dir) {
  if (c.contains("metro") || c.contains("pois"))
    throw std::invalid_argument(where + ": a city with a 'source' takes no 'metro' or 'pois' (they come from it)");
  const auto& sj = c["source"];
  if (!sj.is_object()) throw std::invalid_argument(where + ".source: expected an object");
  CitySourceImport out;
  out.city.id = str(c, "id", where);
  out.city.name = str(c, "name", where);
  out.osm = resolve(data_dir, str(sj, "osm", where + ".source"));
  const auto gtfs = str(sj, "gtfs", where + ".source", false);
  if (!gtfs.empty()) out.gtfs = resolve(data_dir, gtfs);
  out.osm_attribution = str(sj, "attribution", where + ".source", false);
  out.city.attribution = str(sj, "transit_attribution", where + ".source", false);
  out.modes = modes(sj, where + ".source");
  return out;
}

}  // namespace

Manifest parse_manifest(const std::string& json_text, const std::string& data_dir) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::exception& e) {  // parse_error, or out_of_range for a number like 1e309
    throw std::invalid_argument(std::string("manifest is not valid JSON: ") + e.what());
  }
  if (!doc.is_object()) throw std::invalid_argument("manifest must be a JSON object");
  Manifest m;
  for (const auto& c : doc.value("cities", nlohmann::json::array())) {
    std::string where = "cities[" + str(c, "id", "cities[]") + "]";
    if (c.contains("source")) {
      m.sources.push_back(parse_source(c, where, data_dir));
      continue;
    }
    MetroImport metro;
    metro.city.id = str(c, "id", where);
    metro.city.name = str(c, "name", where);
    if (!c.contains("metro") || !c["metro"].is_object()) throw std::invalid_argument(where + ": missing 'metro'");
    const auto& mj = c["metro"];
    metro.format = parse_metro_format(str(mj, "format", where + ".metro"));
    metro.city.attribution = str(mj, "attribution", where + ".metro", false);
    if (!mj.contains("files") || !mj["files"].is_array())
      throw std::invalid_argument(where + ".metro: missing array 'files'");
    for (const auto& f : mj["files"]) {
      if (!f.is_string()) throw std::invalid_argument(where + ".metro.files: expected strings");
      metro.files.push_back(resolve(data_dir, f.get<std::string>()));
    }
    if (mj.contains("rules")) metro.rules = parse_metro_rules(mj["rules"], where + ".metro.rules");
    metro.modes = modes(mj, where + ".metro");
    m.metros.push_back(metro);
    if (c.contains("pois")) {
      const auto& pj = c["pois"];
      PoiImport p;
      p.city_id = metro.city.id;
      p.file = resolve(data_dir, str(pj, "file", where + ".pois"));
      p.default_category = str(pj, "category", where + ".pois", false);
      p.attribution = str(pj, "attribution", where + ".pois", false);
      m.pois.push_back(p);
    }
  }
  for (const auto& r : doc.value("roads", nlohmann::json::array())) {
    std::string where = "roads[" + str(r, "id", "roads[]") + "]";
    RoadImport road;
    road.network.id = str(r, "id", where);
    road.network.name = str(r, "name", where);
    road.network.attribution = str(r, "attribution", where, false);
    road.file = resolve(data_dir, str(r, "file", where));
    m.roads.push_back(road);
  }
  return m;
}

std::vector<ImportResult> run_manifest(Db& db, const Manifest& manifest, bool force,
                                       const std::function<void(const ImportResult&)>& progress,
                                       const load::ImportLimits& limits) {
  std::vector<ImportResult> results;
  auto done = [&](ImportResult r) {
    if (progress) progress(r);
    results.push_back(std::move(r));
  };
  for (auto metro : manifest.metros) {
    metro.force = force;
    done(import_metro(db, metro, limits));
  }
  for (auto pois : manifest.pois) {
    pois.force = force;
    done(import_pois(db, pois, limits));
  }
  for (auto road : manifest.roads) {
    road.force = force;
    done(import_roads(db, road, limits));
  }
  for (auto source : manifest.sources) {
    source.force = force;
    for (auto& r : import_city_source(db, source, limits)) done(std::move(r));
  }
  return results;
}

}  // namespace tourmap::store
