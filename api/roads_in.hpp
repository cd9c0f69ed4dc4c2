#pragma once
// An inline road network from a request body: a GeoJSON FeatureCollection of LineStrings (or
// MultiLineStrings). Positions that are exactly equal become one node; node ids are their
// indices in order of first appearance.

#include "http.hpp"

#include "model/road.hpp"

#include <nlohmann/json.hpp>

namespace tourmap::api {

model::RoadNetwork parse_inline_roads(const nlohmann::json& fc, const std::string& field, std::size_t max_vertices);

}  // namespace tourmap::api
