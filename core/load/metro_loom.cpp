// LOOM line-graph GeoJSON (github.com/ad-freiburg/loom): the de facto exchange format for
// transit line graphs.

#include "load/file.hpp"
#include "load/json_fields.hpp"
#include "load/load_error.hpp"
#include "load/metro_builder.hpp"
#include "load/metro_load.hpp"
#include "util/stop.hpp"

#include <algorithm>

namespace tourmap::load {
namespace {

geo::LonLat parse_position(const nlohmann::json& coord, const std::string& where) {
  if (!coord.is_array() || coord.size() < 2 || !coord[0].is_number() || !coord[1].is_number())
    throw LoadError(where, "coordinates must be [lon, lat]");
  geo::LonLat p{coord[0].get<double>(), coord[1].get<double>()};
  if (!geo::is_valid(p)) throw LoadError(where, "coordinates out of range");
  return p;
}

double squared_deg_distance(geo::LonLat a, geo::LonLat b) {
  double dx = a.lon - b.lon, dy = a.lat - b.lat;
  return dx * dx + dy * dy;
}

}  // namespace

model::MetroNetwork parse_metro_loom(std::string_view json_text_in, const std::string& source,
                                     const ImportLimits& limits, MetroLoadStats* stats) {
  nlohmann::json doc = parse_json(json_text_in, source, limits);
  if (!doc.is_object() || json_text(doc, "type").value_or("") != "FeatureCollection" ||
      !doc.contains("features") || !doc["features"].is_array())
    throw LoadError(source, "expected a GeoJSON FeatureCollection with a 'features' array");
  const auto& features = doc["features"];

  MetroBuilder builder(limits);
  auto where = [&](std::size_t i) { return source + " feature " + std::to_string(i); };

  // Nodes first: edges refer to them by id and may come before them in the file.
  for (std::size_t i = 0; i < features.size(); ++i) {
    if ((i & 4095) == 0) util::check_stop();
    const auto& f = features[i];
    if (!f.is_object() || !f.contains("geometry") || !f["geometry"].is_object())
      throw LoadError(where(i), "feature without a geometry");
    if (json_text(f["geometry"], "type").value_or("") != "Point") continue;
    const auto props = f.value("properties", nlohmann::json::object());
    model::MetroNode node;
    node.id = json_text(props, "id").value_or("");
    if (node.id.empty()) throw LoadError(where(i), "Point feature without properties.id");
    node.station_id = json_text(props, "station_id").value_or("");
    node.name = json_text(props, "station_label").value_or("");
    if (node.is_station() && node.name.empty()) node.name = node.station_id;
    node.pos = parse_position(f["geometry"].value("coordinates", nlohmann::json()), where(i));
    builder.add_node(std::move(node), where(i));
  }

  for (std::size_t i = 0; i < features.size(); ++i) {
    if ((i & 4095) == 0) util::check_stop();
    const auto& f = features[i];
    const auto& geom = f["geometry"];
    auto type = json_text(geom, "type").value_or("");
    if (type == "Point") continue;
    if (type != "LineString") throw LoadError(where(i), "unsupported geometry type '" + type + "'");
    const auto props = f.value("properties", nlohmann::json::object());
    auto from = json_text(props, "from"), to = json_text(props, "to");
    if (!from || !to) throw LoadError(where(i), "LineString feature without properties.from/to");

    model::MetroEdge edge;
    edge.from = builder.node(*from, where(i));
    edge.to = builder.node(*to, where(i));
    const auto coords = geom.value("coordinates", nlohmann::json());
    if (!coords.is_array() || coords.size() < 2) throw LoadError(where(i), "LineString needs at least 2 positions");
    for (const auto& c : coords) edge.geometry.push_back(parse_position(c, where(i)));

    if (props.contains("lines") && props["lines"].is_array()) {
      for (const auto& l : props["lines"]) {
        model::MetroLine line;
        line.label = json_text(l, "label").value_or("");
        line.id = json_text(l, "id").value_or(line.label);
        line.color = json_text(l, "color").value_or("");
        if (!line.color.empty() && line.color[0] == '#') line.color.erase(0, 1);
        if (line.id.empty()) throw LoadError(where(i), "line without id or label");
        if (line.label.empty()) line.label = line.id;
        edge.lines.push_back(builder.line(line, where(i)));
      }
    }
    // LOOM does not promise that the polyline runs from `from` to `to`.
    if (squared_deg_distance(edge.geometry.front(), builder.pos(edge.to)) <
        squared_deg_distance(edge.geometry.front(), builder.pos(edge.from)))
      std::reverse(edge.geometry.begin(), edge.geometry.end());
    builder.add_edge(std::move(edge), where(i));
  }
  if (stats) *stats = builder.stats();
  return std::move(builder).finish(source);
}

model::MetroNetwork load_metro_loom(const std::string& path, const ImportLimits& limits, MetroLoadStats* stats) {
  return parse_metro_loom(read_file(path), file_name(path), limits, stats);
}

}  // namespace tourmap::load
