#include "importer.hpp"

#include "load/file.hpp"
#include "load/load_error.hpp"
#include "load/metro_load.hpp"
#include "load/metro_gtfs.hpp"
#include "load/metro_osm.hpp"
#include "load/name_rules.hpp"
#include "load/osm_context.hpp"
#include "load/osm_roads.hpp"
#include "load/poi_load.hpp"
#include "geo/projection.hpp"
#include "metro/line_styles.hpp"
#include "metro_rules.hpp"
#include "util/hash.hpp"
#include "util/stop.hpp"

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace tourmap::store {
namespace {

using Clock = std::chrono::steady_clock;

// POIs far beyond the city's metro extent are a wrong file or swapped longitude and latitude,
// not sights a metro map can show: the import fails, naming the first such POI. "Far" is
// beyond the extent's diagonal, and at least 50 km.
void check_pois_near_city(const model::CityInfo& city, const std::vector<model::Poi>& pois, const std::string& source) {
  const auto& box = city.bbox;
  if (box.empty()) return;
  const double diagonal = geo::geodesic_distance_m({box.min_lon, box.min_lat}, {box.max_lon, box.max_lat});
  const double limit = std::max(50000.0, diagonal);
  for (std::size_t i = 0; i < pois.size(); ++i) {
    const auto& p = pois[i].pos;
    const geo::LonLat nearest{std::clamp(p.lon, box.min_lon, box.max_lon), std::clamp(p.lat, box.min_lat, box.max_lat)};
    const double off = geo::geodesic_distance_m(p, nearest);
    if (off <= limit) continue;
    char text[512];
    std::snprintf(text, sizeof text,
                  "%s: POI %zu ('%s', id %s) at %.5f,%.5f is %.0f km outside %s's metro network (at most %.0f km "
                  "allowed): a POI file for another city, or longitude and latitude swapped?",
                  source.c_str(), i, pois[i].name.c_str(), pois[i].id.c_str(), p.lon, p.lat, off / 1000, city.id.c_str(),
                  limit / 1000);
    throw std::invalid_argument(text);
  }
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string join_names(const std::vector<std::string>& files) {
  std::string out;
  for (const auto& f : files) out += (out.empty() ? "" : ", ") + load::file_name(f);
  return out;
}

void require_id(const std::string& id, const char* what) {
  if (!is_valid_id(id))
    throw std::invalid_argument(std::string("invalid ") + what + " id '" + id +
                                "': use lower-case letters, digits, '-' and '_' (at most 64)");
}

// "; rules: 171 names cleaned, 1 line hidden (U55bau: 3 edges, 2 stations removed), ..."
std::string rules_summary(const load::RulesReport& r, const load::MetroRules& rules) {
  if (rules.empty()) return "";
  std::string out = "; rules: " + std::to_string(r.names_changed) + " names cleaned";
  if (!r.hidden_lines.empty()) {
    std::string labels;
    for (const auto& l : r.hidden_lines) labels += (labels.empty() ? "" : ", ") + l;
    out += ", " + std::to_string(r.hidden_lines.size()) + " line(s) hidden (" + labels + ": " +
           std::to_string(r.removed_edges) + " edges, " + std::to_string(r.removed_stations) + " stations and " +
           std::to_string(r.removed_junctions) + " junctions removed)";
  }
  if (r.lines_overridden > 0) out += ", " + std::to_string(r.lines_overridden) + " line(s) relabelled or recoloured";
  return out;
}

// "; styles: U55 casing (close to U5)"
std::string styles_summary(const model::MetroNetwork& net, const std::vector<metro::CloseGroup>& groups) {
  std::string out;
  for (const auto& g : groups) {
    const auto& plain = net.lines[g.lines.front()];
    for (std::size_t k = 1; k < g.lines.size(); ++k) {
      const auto& line = net.lines[g.lines[k]];
      out.append(out.empty() ? "; styles: " : ", ").append(line.label).append(" ");
      out.append(metro::describe_style(line.style)).append(" (close to ").append(plain.label).append(")");
    }
  }
  return out;
}

}  // namespace

MetroFormat parse_metro_format(const std::string& name) {
  if (name == "loom") return MetroFormat::loom;
  if (name == "station-csvs") return MetroFormat::station_csvs;
  if (name == "line-csv") return MetroFormat::line_csv;
  if (name == "osm") return MetroFormat::osm;
  if (name == "gtfs") return MetroFormat::gtfs;
  throw std::invalid_argument("unknown metro format '" + name + "' (expected loom, station-csvs, line-csv, osm or gtfs)");
}

std::string fingerprint_files(const std::vector<std::string>& files) {
  // Streamed in chunks: a large extract is not held in memory just to be hashed.
  std::uint64_t h = util::kFnvOffset;
  std::vector<char> buf(1 << 20);
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    if (!in) throw load::LoadError(f, std::string("cannot open: ") + std::strerror(errno));
    while (in) {
      in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
      h = util::fnv1a64(std::string_view(buf.data(), static_cast<std::size_t>(in.gcount())), h);
      util::check_stop();
    }
    if (in.bad()) throw load::LoadError(f, "read failed");
    h = util::fnv1a64("\xff", h);  // file separator
  }
  return util::hex64(h);
}

std::string metro_fingerprint(const std::vector<std::string>& files, const load::MetroRules& rules) {
  auto h = util::fnv1a64(kMetroProcessing);
  h = util::fnv1a64("\xff", h);
  h = util::fnv1a64(metro_rules_json(rules).dump(), h);
  return fingerprint_files(files) + "/" + util::hex64(h);
}

model::MetroNetwork load_metro_files(const MetroImport& req, const load::ImportLimits& limits, load::MetroLoadStats* stats,
                                     std::string* summary, std::vector<std::string>* warnings) {
  switch (req.format) {
    case MetroFormat::loom: return load::load_metro_loom(req.files.at(0), limits, stats);
    case MetroFormat::station_csvs:
      return load::load_metro_station_csvs(req.files.at(0), req.files.at(1), req.files.at(2), limits, stats);
    case MetroFormat::line_csv: return load::load_metro_line_csv(req.files.at(0), limits, stats);
    case MetroFormat::osm: {
      load::OsmTransitStats transit;
      auto net = load::load_metro_osm(req.files.at(0), req.modes, limits, &transit);
      if (summary) {
        std::string modes;
        for (const auto& m : transit.modes) modes += (modes.empty() ? "" : ", ") + m;
        *summary = "; OSM " + modes + ": " + std::to_string(transit.routes) + " routes";
        if (transit.routes_without_stops > 0)
          *summary += " (" + std::to_string(transit.routes_without_stops) +
                      " with fewer than two stops in the extract, not used)";
        *summary += "; track geometry on " + std::to_string(transit.track_edges) + " of " +
                    std::to_string(transit.track_edges + transit.straight_edges) + " edges (" +
                    std::to_string(transit.gaps_repaired) + " breaks between ways repaired, " +
                    std::to_string(transit.gaps) + " gaps left)";
        if (!transit.problems.empty())
          *summary += "; " + std::to_string(transit.problems.size() + transit.problems_left_off) +
                      " route problem(s), e.g. " + transit.problems.front().message;
      }
      if (warnings) {
        for (const auto& p : transit.problems) warnings->push_back(p.message);
        if (transit.problems_left_off > 0)
          warnings->push_back("and " + std::to_string(transit.problems_left_off) + " more route problems");
      }
      return net;
    }
    case MetroFormat::gtfs: {
      load::GtfsStats gtfs;
      auto net = load::load_metro_gtfs(req.files.at(0), req.modes, limits, &gtfs);
      if (summary) {
        std::string modes;
        for (const auto& m : gtfs.modes) modes += (modes.empty() ? "" : ", ") + m;
        *summary = "; GTFS " + modes + ": " + std::to_string(gtfs.lines) + " of " + std::to_string(gtfs.routes) +
                   " routes, " + std::to_string(gtfs.trips_of_modes) + " trips, " + std::to_string(gtfs.patterns) +
                   " stop patterns, " + std::to_string(gtfs.stop_times) + " stop times";
        if (gtfs.shapes_used > 0) *summary += ", " + std::to_string(gtfs.shapes_used) + " shapes";
        if (gtfs.patterns_off_shape > 0)
          *summary += " (" + std::to_string(gtfs.patterns_off_shape) + " patterns off their shape, drawn straight)";
      }
      return net;
    }
  }
  throw std::invalid_argument("unknown metro format");
}

LoadedMetro load_metro_for_import(const MetroImport& req, const load::ImportLimits& limits) {
  load::MetroLoadStats stats;
  std::string osm_summary;  // format osm: the modes and routes read
  LoadedMetro out;
  out.net = load_metro_files(req, limits, &stats, &osm_summary, &out.warnings);
  auto& net = out.net;
  auto cleaned = load::apply_metro_rules(net, req.rules);
  const auto coloured = metro::assign_missing_colours(net);
  auto close = metro::assign_line_styles(net, req.rules.min_colour_difference.value_or(metro::kMinColourDifference));
  out.rows = net.nodes.size() + net.edges.size() + net.lines.size();
  out.summary = std::to_string(net.station_count()) + " stations, " + std::to_string(net.nodes.size()) + " nodes, " +
                std::to_string(net.edges.size()) + " edges, " + std::to_string(net.lines.size()) + " lines";
  if (stats.merged_connections > 0)
    out.summary += " (" + std::to_string(stats.merged_connections) + " of " + std::to_string(stats.connections) +
                   " connections merged into parallel edges)";
  out.summary += osm_summary + rules_summary(cleaned, req.rules) + styles_summary(net, close);
  if (coloured > 0) out.summary += "; " + std::to_string(coloured) + " line(s) without a colour given distinct ones";
  return out;
}

ImportResult import_metro(Db& db, const MetroImport& req, const load::ImportLimits& limits) {
  require_id(req.city.id, "city");
  if (req.city.name.empty()) throw std::invalid_argument("city name is empty");
  std::size_t expected = req.format == MetroFormat::station_csvs ? 3 : 1;
  if (req.files.size() != expected)
    throw std::invalid_argument("metro format needs " + std::to_string(expected) + " file(s), got " +
                                std::to_string(req.files.size()));
  auto start = Clock::now();
  ImportResult result;
  result.kind = "metro";
  result.target = req.city.id;
  if (auto why = load::rules_error(req.rules); !why.empty()) throw std::invalid_argument("rules." + why);
  auto fp = metro_fingerprint(req.files, req.rules);
  for (const auto& mode : req.modes) fp += (&mode == &req.modes.front() ? "/modes=" : ",") + mode;
  if (!req.force && last_fingerprint(db, "metro", req.city.id) == fp && city_version(db, req.city.id)) {
    result.skipped = true;
    result.version = city_version(db, req.city.id).value_or(0);
    return result;
  }
  auto loaded = load_metro_for_import(req, limits);
  result.rows = loaded.rows;
  result.version = save_city_metro(db, req.city, loaded.net,
                                   {"metro", req.city.id, join_names(req.files), fp, result.rows, seconds_since(start)});
  result.seconds = seconds_since(start);
  result.summary = std::move(loaded.summary);
  result.warnings = std::move(loaded.warnings);
  return result;
}

void check_pois_near_city(const model::MetroNetwork& net, const std::string& city_id,
                          const std::vector<model::Poi>& pois, const std::string& source) {
  model::CityInfo info;
  info.id = city_id;
  for (const auto& n : net.nodes) info.bbox.extend(n.pos);
  check_pois_near_city(info, pois, source);
}

ImportResult import_pois(Db& db, const PoiImport& req, const load::ImportLimits& limits) {
  require_id(req.city_id, "city");
  auto start = Clock::now();
  ImportResult result;
  result.kind = "pois";
  result.target = req.city_id;
  if (!city_version(db, req.city_id))
    throw std::invalid_argument("unknown city '" + req.city_id + "': import its metro network first");
  auto fp = fingerprint_files({req.file});
  if (!req.force && last_fingerprint(db, "pois", req.city_id) == fp) {
    result.skipped = true;
    result.version = city_version(db, req.city_id).value_or(0);
    return result;
  }
  auto pois = load::load_pois(req.file, {req.default_category}, limits);
  check_pois_near_city(*find_city(db, req.city_id), pois, load::file_name(req.file));
  result.rows = pois.size();
  result.version = save_city_pois(db, req.city_id, req.attribution, pois,
                                  {"pois", req.city_id, load::file_name(req.file), fp, result.rows,
                                   seconds_since(start)});
  result.seconds = seconds_since(start);
  result.summary = std::to_string(pois.size()) + " POIs";
  return result;
}

LoadedRoads load_roads_for_import(const std::string& file, const load::ImportLimits& limits) {
  LoadedRoads out;
  load::OsmRoadStats stats;
  out.net = load::load_osm_roads(file, &stats, limits);
  load::OsmContextStats context_stats;
  out.context = load::load_osm_context(file, &context_stats, limits);
  const auto& net = out.net;
  const auto& context = out.context;
  out.rows = net.nodes.size() + net.ways.size() + net.edges.size() + context.areas.size() + context.lines.size() +
             context.places.size();
  out.summary = std::to_string(net.nodes.size()) + " nodes, " + std::to_string(net.edges.size()) + " edges, " +
                std::to_string(net.ways.size()) + " ways (of " + std::to_string(stats.osm_ways) +
                " OSM ways); context: " + std::to_string(context.areas.size()) + " areas (" +
                std::to_string(context_stats.sea_rings) + " sea), " + std::to_string(context.lines.size()) +
                " lines, " + std::to_string(context.places.size()) + " places";
  return out;
}

ImportResult import_roads(Db& db, const RoadImport& req, const load::ImportLimits& limits) {
  require_id(req.network.id, "road network");
  if (req.network.name.empty()) throw std::invalid_argument("road network name is empty");
  auto start = Clock::now();
  ImportResult result;
  result.kind = "roads";
  result.target = req.network.id;
  const auto fp = fingerprint_files({req.file}) + "/" + util::hex64(util::fnv1a64(kRoadProcessing));
  if (!req.force && last_fingerprint(db, "roads", req.network.id) == fp && road_network_version(db, req.network.id)) {
    result.skipped = true;
    result.version = road_network_version(db, req.network.id).value_or(0);
    return result;
  }
  auto loaded = load_roads_for_import(req.file, limits);
  result.rows = loaded.rows;
  result.version = save_road_network(db, req.network, loaded.net,
                                     {"roads", req.network.id, load::file_name(req.file), fp, result.rows,
                                      seconds_since(start)},
                                     loaded.context);
  result.seconds = seconds_since(start);
  result.summary = std::move(loaded.summary);
  return result;
}

}  // namespace tourmap::store
