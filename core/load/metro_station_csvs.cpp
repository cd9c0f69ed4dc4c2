// Station / line / connection CSV triple (the London Underground data set).

#include "load/csv.hpp"
#include "load/file.hpp"
#include "load/load_error.hpp"
#include "load/metro_builder.hpp"
#include "load/metro_load.hpp"

#include <unordered_map>

namespace tourmap::load {

model::MetroNetwork parse_metro_station_csvs(const LondonCsvText& files, const ImportLimits& limits,
                                             MetroLoadStats* stats) {
  MetroBuilder builder(limits);

  CsvReader stations(files.stations, files.stations_source, limits);
  auto s_id = stations.column({"id"});
  auto s_lat = stations.column({"latitude", "lat"});
  auto s_lon = stations.column({"longitude", "lon", "lng"});
  auto s_name = stations.column({"name"});
  while (stations.next()) {
    auto& row = stations.row();
    auto where = stations.where();
    model::MetroNode node;
    node.pos.lat = parse_number(row[s_lat], where, "latitude");
    node.pos.lon = parse_number(row[s_lon], where, "longitude");
    node.id = row[s_id];
    node.station_id = std::move(row[s_id]);
    node.name = std::move(row[s_name]);
    builder.add_node(std::move(node), where);
  }

  CsvReader lines(files.lines, files.lines_source, limits);
  auto l_id = lines.column({"line", "id"});
  auto l_name = lines.column({"name"});
  auto l_color = lines.find_column({"colour", "color"});
  std::unordered_map<std::string, model::MetroLine> line_by_id;
  while (lines.next()) {
    const auto& row = lines.row();
    model::MetroLine line{row[l_id], row[l_name], l_color ? row[*l_color] : ""};
    if (is_null_field(line.color)) line.color.clear();
    if (!line.color.empty() && line.color[0] == '#') line.color.erase(0, 1);
    // The same checks the builder makes when a connection first uses the line, made here so
    // that a lines file of unused lines cannot grow without bound either.
    check_text(line.id, limits.max_id_bytes, "max_id_bytes", lines.where(), "line id");
    check_text(line.label, limits.max_name_bytes, "max_name_bytes", lines.where(), "line name");
    check_text(line.color, limits.max_id_bytes, "max_id_bytes", lines.where(), "line colour");
    check_limit(line_by_id.size() + 1, limits.max_metro_lines, "max_metro_lines", lines.where(), "lines");
    if (!line_by_id.emplace(line.id, line).second)
      throw LoadError(lines.where(), "duplicate line id '" + line.id + "'");
  }

  CsvReader conns(files.connections, files.connections_source, limits);
  auto c_a = conns.column({"station1", "from"});
  auto c_b = conns.column({"station2", "to"});
  auto c_line = conns.column({"line"});
  while (conns.next()) {
    const auto& row = conns.row();
    auto where = conns.where();
    auto it = line_by_id.find(row[c_line]);
    if (it == line_by_id.end()) throw LoadError(where, "unknown line '" + row[c_line] + "'");
    auto line = builder.line(it->second, where);
    builder.connect(builder.node(row[c_a], where), builder.node(row[c_b], where), line, where);
  }
  if (stats) *stats = builder.stats();
  return std::move(builder).finish(files.stations_source);
}

model::MetroNetwork load_metro_station_csvs(const std::string& stations_path, const std::string& lines_path,
                                            const std::string& connections_path, const ImportLimits& limits,
                                            MetroLoadStats* stats) {
  std::string stations = read_file(stations_path), lines = read_file(lines_path),
              connections = read_file(connections_path);
  return parse_metro_station_csvs({stations, lines, connections, file_name(stations_path), file_name(lines_path),
                                   file_name(connections_path)},
                                  limits, stats);
}

}  // namespace tourmap::load
