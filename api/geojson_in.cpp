#include "geojson_in.hpp"

#include "params.hpp"

#include <cmath>

namespace tourmap::api {
namespace {

ApiError bad_geojson(const std::string& field, const std::string& message) {
  return bad(field, message, "invalid_geojson");
}

std::vector<geo::LonLat> parse_ring(const nlohmann::json& value, const std::string& field, std::size_t& budget) {
  if (!value.is_array()) throw bad_geojson(field, "a ring must be an array of positions");
  if (value.size() < 4) throw bad_geojson(field, "a ring needs at least 4 positions (closed)");
  if (value.size() > budget) throw too_large(field, "too many vertices");
  budget -= value.size();
  std::vector<geo::LonLat> ring;
  for (std::size_t i = 0; i < value.size(); ++i)
    ring.push_back(parse_position(value[i], field + "[" + std::to_string(i) + "]"));
  if (ring.front().lon != ring.back().lon || ring.front().lat != ring.back().lat)
    throw bad_geojson(field, "a ring must end where it starts");
  ring.pop_back();
  if (!geo::is_simple_ring(ring)) throw bad_geojson(field, "the ring intersects itself or has zero area");
  return ring;
}

geo::Polygon parse_polygon_coords(const nlohmann::json& value, const std::string& field, std::size_t& budget) {
  if (!value.is_array() || value.empty()) throw bad_geojson(field, "a Polygon needs at least one ring");
  geo::Polygon poly;
  poly.outer = parse_ring(value[0], field + "[0]", budget);
  for (std::size_t i = 1; i < value.size(); ++i)
    poly.holes.push_back(parse_ring(value[i], field + "[" + std::to_string(i) + "]", budget));
  return poly;
}

}  // namespace

geo::LonLat parse_position(const nlohmann::json& value, const std::string& field) {
  if (!value.is_array() || value.size() < 2 || value.size() > 3 || !value[0].is_number() || !value[1].is_number())
    throw bad_geojson(field, "a position is [lon, lat]");
  geo::LonLat p{value[0].get<double>(), value[1].get<double>()};
  if (!geo::is_valid(p)) throw bad_geojson(field, "lon must be in [-180, 180] and lat in [-90, 90]");
  return p;
}

std::vector<geo::Polygon> parse_polygons(const nlohmann::json& value, const std::string& field,
                                         const GeoJsonLimits& limits) {
  if (!value.is_object()) throw bad_geojson(field, "expected a GeoJSON Polygon, MultiPolygon or Feature");
  auto type_it = value.find("type");
  if (type_it == value.end() || !type_it->is_string()) throw bad_geojson(field + ".type", "missing 'type'");
  const auto& type = type_it->get_ref<const std::string&>();
  if (type == "Feature") {
    if (!value.contains("geometry")) throw bad_geojson(field + ".geometry", "a Feature needs a geometry");
    return parse_polygons(value["geometry"], field + ".geometry", limits);
  }
  auto coords = value.find("coordinates");
  if (coords == value.end()) throw bad_geojson(field + ".coordinates", "missing 'coordinates'");
  std::size_t budget = limits.max_vertices;
  if (type == "Polygon") return {parse_polygon_coords(*coords, field + ".coordinates", budget)};
  if (type == "MultiPolygon") {
    if (!coords->is_array() || coords->empty()) throw bad_geojson(field + ".coordinates", "a MultiPolygon needs polygons");
    std::vector<geo::Polygon> out;
    for (std::size_t i = 0; i < coords->size(); ++i)
      out.push_back(parse_polygon_coords((*coords)[i], field + ".coordinates[" + std::to_string(i) + "]", budget));
    return out;
  }
  throw bad_geojson(field + ".type", "expected Polygon, MultiPolygon or Feature, got '" + type + "'");
}

}  // namespace tourmap::api
