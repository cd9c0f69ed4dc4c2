#pragma once
// The context layers of a road network as JSON (GET /api/v1/roads/{id}/context, openapi.yaml):
// areas, lines and places with coordinates as flat [lon, lat, lon, lat, ...] arrays rounded to
// 1e-6 degrees (about 0.1 m), each line and ring simplified to `simplify_m` metres
// (Douglas-Peucker); rings that shrink below 3 points and areas smaller than the tolerance's
// square are left out, so a coarse request is small.

#include "catalog.hpp"
#include "http.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tourmap::api {

struct ContextQuery {
  double simplify_m = 1.0;
  std::vector<std::string> kinds;  // area, line and place kind names to keep; empty: all
};

// Parses `simplify_m` (0-1000, default 1) and `kinds` (comma-separated kind names; an unknown
// one is refused naming the field).
ContextQuery parse_context_query(const Request& req);

nlohmann::json road_context_json(const RoadNetworkEntry& entry, const ContextQuery& q);

}  // namespace tourmap::api
