#pragma once
// Query-string and body validation. Every failure is an ApiError 400 naming the field.

#include "http.hpp"

#include "geo/lonlat.hpp"

#include <optional>
#include <string>

namespace tourmap::api {

// bbox=min_lon,min_lat,max_lon,max_lat: four finite numbers within WGS84, min <= max.
std::optional<geo::BBox> query_bbox(const Request& req, const std::string& name = "bbox");
geo::BBox parse_bbox(const std::string& text, const std::string& field);
geo::BBox parse_bbox_json(const nlohmann::json& value, const std::string& field);

// An integer parameter in [min, max]; `fallback` when absent.
long long query_int(const Request& req, const std::string& name, long long min, long long max, long long fallback);
// true/false/1/0; `fallback` when absent.
bool query_bool(const Request& req, const std::string& name, bool fallback);

// A path id: a url-safe slug, else 404 (no such resource can exist).
void require_slug(const std::string& id, const std::string& what, const std::string& field = "id");

// Parses a JSON request body: 415 unless the content type is JSON, 400 on syntax errors.
nlohmann::json parse_json_body(const Request& req);

}  // namespace tourmap::api
