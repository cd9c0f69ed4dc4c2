#include "load/import_limits.hpp"

#include <type_traits>

namespace tourmap::load {
namespace {

// Every limit once, with its name: list_limits and set_limit share this table.
template <class F>
void for_each_limit(ImportLimits& l, F&& f) {
  f("max_pois", l.max_pois, "count");
  f("max_metro_nodes", l.max_metro_nodes, "count");
  f("max_metro_edges", l.max_metro_edges, "count");
  f("max_metro_lines", l.max_metro_lines, "count");
  f("max_metro_connections", l.max_metro_connections, "count");
  f("max_metro_geometry_points", l.max_metro_geometry_points, "count");
  f("max_osm_decompressed_bytes", l.max_osm_decompressed_bytes, "bytes");
  f("max_osm_pbf_blobs", l.max_osm_pbf_blobs, "count");
  f("max_osm_nodes", l.max_osm_nodes, "count");
  f("max_osm_ways", l.max_osm_ways, "count");
  f("max_osm_relations", l.max_osm_relations, "count");
  f("max_osm_track_points", l.max_osm_track_points, "count");
  f("max_road_nodes", l.max_road_nodes, "count");
  f("max_road_ways", l.max_road_ways, "count");
  f("max_road_edges", l.max_road_edges, "count");
  f("max_context_points", l.max_context_points, "count");
  f("max_gtfs_file_bytes", l.max_gtfs_file_bytes, "bytes");
  f("max_gtfs_rows", l.max_gtfs_rows, "count");
  f("max_gtfs_stops", l.max_gtfs_stops, "count");
  f("max_gtfs_trips", l.max_gtfs_trips, "count");
  f("max_gtfs_buffered_stop_times", l.max_gtfs_buffered_stop_times, "count");
  f("max_gtfs_shape_points", l.max_gtfs_shape_points, "count");
  f("max_id_bytes", l.max_id_bytes, "bytes");
  f("max_name_bytes", l.max_name_bytes, "bytes");
  f("max_url_bytes", l.max_url_bytes, "bytes");
  f("max_csv_fields", l.max_csv_fields, "count");
  f("max_csv_field_bytes", l.max_csv_field_bytes, "bytes");
  f("max_json_values", l.max_json_values, "count");
}

}  // namespace

std::vector<ImportLimitInfo> list_limits(const ImportLimits& limits) {
  std::vector<ImportLimitInfo> out;
  ImportLimits copy = limits;
  for_each_limit(copy, [&](std::string_view name, auto value, std::string_view unit) {
    out.push_back({name, static_cast<std::uint64_t>(value), unit});
  });
  return out;
}

bool set_limit(ImportLimits& limits, std::string_view name, std::uint64_t value) {
  bool found = false;
  for_each_limit(limits, [&](std::string_view n, auto& member, std::string_view) {
    if (n != name) return;
    using T = std::remove_reference_t<decltype(member)>;
    member = value > static_cast<std::uint64_t>(static_cast<T>(-1)) ? static_cast<T>(-1) : static_cast<T>(value);
    found = true;
  });
  return found;
}

void check_limit(std::uint64_t count, std::uint64_t limit, std::string_view limit_name, const std::string& where,
                 std::string_view what) {
  if (count <= limit) return;
  throw LimitExceeded(where, "more than " + std::to_string(limit) + " " + std::string(what), std::string(limit_name),
                      limit);
}

void check_text(std::string_view text, std::size_t limit, std::string_view limit_name, const std::string& where,
                std::string_view field) {
  if (text.size() <= limit) return;
  throw LimitExceeded(where,
                      std::string(field) + " is " + std::to_string(text.size()) + " bytes long, more than " +
                          std::to_string(limit),
                      std::string(limit_name), limit);
}

}  // namespace tourmap::load
