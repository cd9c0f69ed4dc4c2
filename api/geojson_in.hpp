#pragma once
// GeoJSON input validation for request bodies. Errors are ApiError 400 naming the field path,
// e.g. "within.coordinates[0][3]".

#include "http.hpp"

#include "geo/polygon.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tourmap::api {

struct GeoJsonLimits {
  std::size_t max_vertices = 10000;  // over all rings
};

// A Polygon, MultiPolygon, or a Feature holding one. Rings must be closed, have >= 4
// positions, be simple and enclose a non-zero area.
std::vector<geo::Polygon> parse_polygons(const nlohmann::json& value, const std::string& field,
                                         const GeoJsonLimits& limits = {});

// One [lon, lat] position.
geo::LonLat parse_position(const nlohmann::json& value, const std::string& field);

}  // namespace tourmap::api
