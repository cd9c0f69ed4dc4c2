#pragma once
// Metro network loaders. Each returns a validated MetroNetwork or throws LoadError naming the
// record. Validation common to all: unique node ids, finite coordinates, edges between known
// nodes, no self-loops. Parallel connections (the same two nodes) become one edge carrying the
// union of their lines, with the first one's geometry. Beyond an ImportLimits limit they throw
// LimitExceeded (a LoadError) at the first record in excess; they poll util::check_stop().

#include "load/import_limits.hpp"
#include "model/metro.hpp"

#include <cstddef>
#include <string>
#include <string_view>

namespace tourmap::load {

struct MetroLoadStats {
  std::size_t connections = 0;         // edge records read (LOOM LineStrings, connection rows, line stops)
  std::size_t merged_connections = 0;  // of those, merged into an edge between the same nodes
};

// LOOM line graph GeoJSON: Point features {id, station_id?, station_label?}; LineString
// features {from, to, lines: [{id, label, color}]} with the track polyline.
model::MetroNetwork parse_metro_loom(std::string_view json_text, const std::string& source,
                                     const ImportLimits& limits = {}, MetroLoadStats* stats = nullptr);

// Station / line / connection CSVs (the London Underground set): stations(id, latitude,
// longitude, name), lines(line, name, colour), connections(station1, station2, line).
struct LondonCsvText {
  std::string_view stations, lines, connections;
  std::string stations_source, lines_source, connections_source;
};
model::MetroNetwork parse_metro_station_csvs(const LondonCsvText& files, const ImportLimits& limits = {},
                                             MetroLoadStats* stats = nullptr);

// Line-ordered station CSV (the Lisbon set): one row per (line, station) with the position along
// the line: line_id, seq_on_line, name, lat, lon; optional line_en/line_local labels, color and
// gtfs_stop_id. Consecutive stations of a line become edges.
model::MetroNetwork parse_metro_line_csv(std::string_view csv_text, const std::string& source,
                                         const ImportLimits& limits = {}, MetroLoadStats* stats = nullptr);

// File-reading wrappers.
model::MetroNetwork load_metro_loom(const std::string& path, const ImportLimits& limits = {},
                                    MetroLoadStats* stats = nullptr);
model::MetroNetwork load_metro_station_csvs(const std::string& stations_path, const std::string& lines_path,
                                            const std::string& connections_path, const ImportLimits& limits = {},
                                            MetroLoadStats* stats = nullptr);
model::MetroNetwork load_metro_line_csv(const std::string& path, const ImportLimits& limits = {},
                                        MetroLoadStats* stats = nullptr);

}  // namespace tourmap::load
