#include "roads_in.hpp"

#include "geojson_in.hpp"
#include "params.hpp"

#include <cstring>
#include <map>

namespace tourmap::api {
namespace {

ApiError bad_geojson(const std::string& field, const std::string& message) {
  return bad(field, message, "invalid_geojson");
}

// "type" when it is a string, else "" (json::value("type", "") throws type_error for others).
std::string type_of(const nlohmann::json& obj) {
  auto it = obj.find("type");
  return it != obj.end() && it->is_string() ? it->get<std::string>() : std::string();
}

}  // namespace

model::RoadNetwork parse_inline_roads(const nlohmann::json& fc, const std::string& field, std::size_t max_vertices) {
  if (!fc.is_object() || type_of(fc) != "FeatureCollection" || !fc.contains("features") ||
      !fc["features"].is_array())
    throw bad_geojson(field, "expected a GeoJSON FeatureCollection of LineStrings");
  model::RoadNetwork net;
  std::map<std::pair<double, double>, std::uint32_t> node_at;
  std::size_t vertices = 0;
  const auto& features = fc["features"];
  for (std::size_t i = 0; i < features.size(); ++i) {
    auto f_field = field + ".features[" + std::to_string(i) + "]";
    const auto& f = features[i];
    if (!f.is_object() || !f.contains("geometry") || !f["geometry"].is_object())
      throw bad_geojson(f_field, "a Feature with a geometry");
    const auto& g = f["geometry"];
    auto type = type_of(g);
    std::vector<const nlohmann::json*> lines;
    if (!g.contains("coordinates") || !g["coordinates"].is_array()) throw bad_geojson(f_field + ".geometry", "missing coordinates");
    if (type == "LineString") {
      lines.push_back(&g["coordinates"]);
    } else if (type == "MultiLineString") {
      for (const auto& l : g["coordinates"]) lines.push_back(&l);
    } else {
      throw bad_geojson(f_field + ".geometry.type", "expected LineString or MultiLineString, got '" + type + "'");
    }
    const auto props = f.value("properties", nlohmann::json::object());
    for (const auto* line : lines) {
      if (!line->is_array() || line->size() < 2) throw bad_geojson(f_field + ".geometry", "a line needs at least 2 positions");
      vertices += line->size();
      if (vertices > max_vertices)
        throw too_large(field, "more than " + std::to_string(max_vertices) + " vertices");
      model::RoadWay way;
      way.osm_id = static_cast<std::int64_t>(i);
      way.highway = props.is_object() && props.contains("highway") && props["highway"].is_string()
                        ? props["highway"].get<std::string>()
                        : "road";
      if (props.is_object() && props.contains("name") && props["name"].is_string()) way.name = props["name"];
      for (std::size_t k = 0; k < line->size(); ++k) {
        auto p = parse_position((*line)[k], f_field + ".geometry.coordinates[" + std::to_string(k) + "]");
        auto [it, inserted] = node_at.emplace(std::make_pair(p.lon, p.lat), static_cast<std::uint32_t>(net.nodes.size()));
        if (inserted) net.nodes.push_back({static_cast<std::int64_t>(it->second), p});
        if (way.nodes.empty() || way.nodes.back() != it->second) way.nodes.push_back(it->second);
      }
      if (way.nodes.size() >= 2) net.ways.push_back(std::move(way));
    }
  }
  net.edges = model::edges_of(net.ways);
  if (net.edges.empty()) throw bad_geojson(field, "the road network is empty (no line with two distinct positions)");
  return net;
}

}  // namespace tourmap::api
