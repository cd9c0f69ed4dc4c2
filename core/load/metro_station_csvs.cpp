// Station / line / connection CSV triple (the London Underground data set).

#include "load/csv.hpp"
#include "load/file.hpp"
#include "load/load_error.hpp"
#include "load/metro_builder.hpp"
#include "load/metro_load.hpp"

#include <unordered_map>

namespace tourmap::load {

model::MetroNetwork parse_metro_station_csvs(const LondonCsvText& files) {
  MetroBuilder builder;

  auto stations = parse_csv(files.stations, files.stations_source);
  auto s_id = stations.column({"id"});
  auto s_lat = stations.column({"latitude", "lat"});
  auto s_lon = stations.column({"longitude", "lon", "lng"});
  auto s_name = stations.column({"name"});
  for (std::size_t r = 0; r < stations.rows.size(); ++r) {
    const auto& row = stations.rows[r];
    model::MetroNode node;
    node.id = row[s_id];
    node.station_id = row[s_id];
    node.name = row[s_name];
    node.pos.lat = parse_number(row[s_lat], stations.where(r), "latitude");
    node.pos.lon = parse_number(row[s_lon], stations.where(r), "longitude");
    builder.add_node(std::move(node), stations.where(r));
  }

  auto lines = parse_csv(files.lines, files.lines_source);
  auto l_id = lines.column({"line", "id"});
  auto l_name = lines.column({"name"});
  auto l_color = lines.find_column({"colour", "color"});
  std::unordered_map<std::string, model::MetroLine> line_by_id;
  for (std::size_t r = 0; r < lines.rows.size(); ++r) {
    const auto& row = lines.rows[r];
    model::MetroLine line{row[l_id], row[l_name], l_color ? row[*l_color] : ""};
    if (is_null_field(line.color)) line.color.clear();
    if (!line.color.empty() && line.color[0] == '#') line.color.erase(0, 1);
    if (!line_by_id.emplace(line.id, line).second)
      throw LoadError(lines.where(r), "duplicate line id '" + line.id + "'");
  }

  auto conns = parse_csv(files.connections, files.connections_source);
  auto c_a = conns.column({"station1", "from"});
  auto c_b = conns.column({"station2", "to"});
  auto c_line = conns.column({"line"});
  for (std::size_t r = 0; r < conns.rows.size(); ++r) {
    const auto& row = conns.rows[r];
    auto it = line_by_id.find(row[c_line]);
    if (it == line_by_id.end()) throw LoadError(conns.where(r), "unknown line '" + row[c_line] + "'");
    auto line = builder.line(it->second);
    builder.connect(builder.node(row[c_a], conns.where(r)), builder.node(row[c_b], conns.where(r)), line,
                    conns.where(r));
  }
  return std::move(builder).finish(files.stations_source);
}

model::MetroNetwork load_metro_station_csvs(const std::string& stations_path, const std::string& lines_path,
                                            const std::string& connections_path) {
  std::string stations = read_file(stations_path), lines = read_file(lines_path),
              connections = read_file(connections_path);
  return parse_metro_station_csvs({stations, lines, connections, file_name(stations_path), file_name(lines_path),
                                   file_name(connections_path)});
}

}  // namespace tourmap::load
