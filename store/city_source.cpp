#include "city_source.hpp"

#include "load/file.hpp"
#include "load/osm_pois.hpp"
#include "util/hash.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <stdexcept>

namespace tourmap::store {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kOsmAttribution = "© OpenStreetMap contributors (ODbL 1.0)";
constexpr int kSteps = 5;  // transit, pois, roads, writing, done

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The files whose bytes make the source: the extract, and the feed's files (a folder's in name order).
std::vector<std::string> source_files(const CitySourceImport& req) {
  std::vector<std::string> files{req.osm};
  if (req.gtfs.empty()) return files;
  if (!std::filesystem::is_directory(req.gtfs)) {
    files.push_back(req.gtfs);
    return files;
  }
  std::vector<std::string> feed;
  for (const auto& entry : std::filesystem::directory_iterator(req.gtfs))
    if (entry.is_regular_file() && entry.path().extension() == ".txt") feed.push_back(entry.path().string());
  std::sort(feed.begin(), feed.end());
  files.insert(files.end(), feed.begin(), feed.end());
  return files;
}

void validate(const CitySourceImport& req) {
  if (!is_valid_id(req.city.id))
    throw std::invalid_argument("invalid city id '" + req.city.id +
                                "': use lower-case letters, digits, '-' and '_' (at most 64)");
  if (req.city.name.empty()) throw std::invalid_argument("city name is empty");
  if (req.osm.empty()) throw std::invalid_argument("no OSM extract given");
  if (!load::is_osm_file_name(load::file_name(req.osm)))
    throw std::invalid_argument("osm: '" + load::file_name(req.osm) +
                                "' is not an OSM extract (.osm, .osm.gz, .osm.bz2, .osm.pbf)");
  if (!std::filesystem::exists(req.osm)) throw std::invalid_argument("osm: no such file '" + req.osm + "'");
  if (!req.gtfs.empty() && !std::filesystem::exists(req.gtfs))
    throw std::invalid_argument("gtfs: no such file or folder '" + req.gtfs + "'");
}

class Progress {
 public:
  explicit Progress(const CitySourceImport& req) : req_(req) {}
  void operator()(const char* stage, std::string detail = "") {
    ++step_;
    if (req_.progress) req_.progress({req_.city.id, stage, step_, kSteps, std::move(detail)});
  }

 private:
  const CitySourceImport& req_;
  int step_ = 0;
};

bool unchanged(Db& db, const CitySourceImport& req, const std::string& fp) {
  const auto& id = req.city.id;
  return last_fingerprint(db, "metro", id) == fp && last_fingerprint(db, "pois", id) == fp &&
         last_fingerprint(db, "roads", id) == fp && city_version(db, id) && road_network_version(db, id);
}

}  // namespace

std::string city_source_fingerprint(const CitySourceImport& req) {
  std::string fp = fingerprint_files(source_files(req));
  for (const auto& mode : req.modes) fp += (&mode == &req.modes.front() ? "/modes=" : ",") + mode;
  return fp + "/" + util::hex64(util::fnv1a64(std::string(kCitySourceProcessing) + kMetroProcessing + kRoadProcessing));
}

std::vector<ImportResult> import_city_source(Db& db, const CitySourceImport& req, const load::ImportLimits& limits) {
  validate(req);
  const auto start = Clock::now();
  const auto& id = req.city.id;
  const auto fp = city_source_fingerprint(req);
  std::vector<ImportResult> results(3);
  const char* kinds[] = {"metro", "pois", "roads"};
  for (int k = 0; k < 3; ++k) {
    results[k].kind = kinds[k];
    results[k].target = id;
  }
  if (!req.force && unchanged(db, req, fp)) {
    for (auto& r : results) {
      r.skipped = true;
      r.version = r.kind == "roads" ? road_network_version(db, id).value_or(0) : city_version(db, id).value_or(0);
    }
    return results;
  }
  Progress progress(req);

  // Load everything before writing anything: a fault in any part changes nothing.
  progress("transit");
  MetroImport transit;
  transit.city = req.city;
  const std::string osm_attribution = req.osm_attribution.empty() ? kOsmAttribution : req.osm_attribution;
  // A feed's own credit is in its agency.txt, not read here: name the feed rather than claim OSM.
  if (transit.city.attribution.empty())
    transit.city.attribution = req.gtfs.empty() ? osm_attribution : "GTFS feed " + load::file_name(req.gtfs);
  transit.format = req.gtfs.empty() ? MetroFormat::osm : MetroFormat::gtfs;
  transit.files = {req.gtfs.empty() ? req.osm : req.gtfs};
  transit.modes = req.modes;
  auto metro = load_metro_for_import(transit, limits);
  results[0].rows = metro.rows;
  results[0].summary = metro.summary;
  results[0].warnings = metro.warnings;

  progress("pois", results[0].summary);
  load::OsmPoiStats poi_stats;
  const auto pois = load::load_osm_pois(req.osm, &poi_stats, limits);
  check_pois_near_city(metro.net, id, pois, load::file_name(req.osm));
  results[1].rows = pois.size();
  results[1].summary = std::to_string(pois.size()) + " POIs";

  progress("roads", results[1].summary);
  auto roads = load_roads_for_import(req.osm, limits);
  results[2].rows = roads.rows;
  results[2].summary = roads.summary;

  progress("writing", results[2].summary);
  const auto source = load::file_name(req.osm) + (req.gtfs.empty() ? "" : ", " + load::file_name(req.gtfs));
  const double load_seconds = seconds_since(start);
  {
    Transaction tx(db);
    results[0].version = save_city_metro(db, transit.city, metro.net, {"metro", id, source, fp, metro.rows, load_seconds});
    results[1].version = save_city_pois(db, id, osm_attribution, pois, {"pois", id, source, fp, pois.size(), load_seconds});
    results[2].version = save_road_network(db, {id, req.city.name, osm_attribution}, roads.net,
                                           {"roads", id, source, fp, roads.rows, load_seconds}, roads.context);
    tx.commit();
  }
  const double seconds = seconds_since(start);
  for (auto& r : results) r.seconds = seconds;
  progress("done");
  return results;
}

}  // namespace tourmap::store
