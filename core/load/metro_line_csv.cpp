// Line-ordered station CSV (the Lisbon data set): one row per station per line, with its
// position along the line.

#include "load/csv.hpp"
#include "load/file.hpp"
#include "load/load_error.hpp"
#include "load/metro_builder.hpp"
#include "load/metro_load.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <unordered_map>

namespace tourmap::load {
namespace {

// Lines named after a colour (Lisbon: Azul/Blue, Amarela/Yellow, ...) get that colour when the
// file has no colour column.
std::string colour_from_name(std::string name) {
  for (auto& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static const std::map<std::string, std::string> named = {
      {"blue", "0072bc"},   {"yellow", "ffc20e"}, {"green", "00a651"}, {"red", "ed1c24"},
      {"orange", "f7941d"}, {"purple", "92278f"}, {"brown", "8b5a2b"}, {"pink", "f49ac1"},
      {"grey", "8c8c8c"},   {"gray", "8c8c8c"},   {"black", "231f20"}};
  auto it = named.find(name);
  return it == named.end() ? "" : it->second;
}

}  // namespace

model::MetroNetwork parse_metro_line_csv(std::string_view csv_text, const std::string& source,
                                         const ImportLimits& limits, MetroLoadStats* stats) {
  CsvReader table(csv_text, source, limits);
  auto c_line = table.column({"line_id", "line"});
  auto c_seq = table.column({"seq_on_line", "seq", "sequence"});
  auto c_name = table.column({"name", "station", "station_name"});
  auto c_lat = table.column({"lat", "latitude"});
  auto c_lon = table.column({"lon", "lng", "longitude"});
  auto c_label = table.find_column({"line_local", "line_name", "line_label"});
  auto c_label_en = table.find_column({"line_en"});
  auto c_color = table.find_column({"color", "colour", "line_color"});
  auto c_station = table.find_column({"gtfs_stop_id", "station_id", "stop_id"});

  MetroBuilder builder(limits);
  // (line id) -> (seq -> (node, line of the row)) to connect consecutive stations afterwards.
  std::map<std::string, std::map<double, std::pair<std::uint32_t, std::size_t>>> sequence;
  std::size_t stops = 0;

  while (table.next()) {
    const auto& row = table.row();
    auto where = table.where();
    // Every stop but a line's first becomes a connection: bound them before storing them.
    check_limit(++stops, limits.max_metro_connections, "max_metro_connections", where, "line stops");
    // A transfer station appears once per line: identify it by stop id, else by name.
    std::string station_id = c_station && !is_null_field(row[*c_station]) ? row[*c_station] : row[c_name];
    if (station_id.empty()) throw LoadError(where, "station without name or id");
    geo::LonLat pos{parse_number(row[c_lon], where, "lon"), parse_number(row[c_lat], where, "lat")};
    if (!builder.has_node(station_id)) builder.add_node({station_id, station_id, row[c_name], pos}, where);

    model::MetroLine line;
    line.id = row[c_line];
    if (line.id.empty()) throw LoadError(where, "empty line id");
    line.label = c_label && !is_null_field(row[*c_label]) ? row[*c_label] : line.id;
    line.color = c_color && !is_null_field(row[*c_color]) ? row[*c_color] : "";
    if (line.color.empty() && c_label_en) line.color = colour_from_name(row[*c_label_en]);
    if (line.color.empty()) line.color = colour_from_name(line.label);
    builder.line(line, where);

    double seq = parse_number(row[c_seq], where, "seq_on_line");
    auto& line_stops = sequence[line.id];
    if (!line_stops.emplace(seq, std::make_pair(builder.node(station_id, where), table.line())).second)
      throw LoadError(where, "line '" + line.id + "' has two stations at position " + row[c_seq]);
  }

  for (const auto& [line_id, line_stops] : sequence) {
    auto line = builder.line({line_id, "", ""});
    for (auto it = line_stops.begin(); std::next(it) != line_stops.end(); ++it) {
      auto next = std::next(it);
      builder.connect(it->second.first, next->second.first, line, source + " line " + std::to_string(next->second.second));
    }
  }
  if (stats) *stats = builder.stats();
  return std::move(builder).finish(source);
}

model::MetroNetwork load_metro_line_csv(const std::string& path, const ImportLimits& limits, MetroLoadStats* stats) {
  return parse_metro_line_csv(read_file(path), file_name(path), limits, stats);
}

}  // namespace tourmap::load
