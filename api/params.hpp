#pragma once
// The validation kit every handler uses: one way to refuse a field, and typed readers of query
// parameters and JSON members. Every failure is an ApiError naming the field, with a message
// that starts with the field: "radius_m: must be between 0.001 and 10000000".

#include "http.hpp"

#include "geo/lonlat.hpp"

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

namespace tourmap::api {

// --- refusals ---
// 400: "<field>: <message>"; `code` defaults to invalid_parameter.
ApiError bad(const std::string& field, const std::string& message, const std::string& code = "invalid_parameter");
// 413 too_large: a count or size beyond a documented limit.
ApiError too_large(const std::string& field, const std::string& message);
// 404 not_found: "<field>: no <what> '<id>'".
ApiError not_found(const std::string& field, const std::string& what, const std::string& id);
// A client's text as shown inside a message: at most 64 bytes (then "..."), control
// characters (a NUL among them) as \xNN.
std::string shown(std::string_view client_text);

// --- JSON members (bodies, WebSocket messages) ---
const nlohmann::json* member(const nlohmann::json& object, const char* key);
// Fields an object may have; any other is refused as "<prefix>.<key>: unknown field".
void reject_unknown(const nlohmann::json& object, const std::string& prefix, std::initializer_list<const char*> known);
double json_number(const nlohmann::json& v, const std::string& field, double min, double max);
long long json_integer(const nlohmann::json& v, const std::string& field, long long min, long long max);
bool json_bool(const nlohmann::json& v, const std::string& field);
// One of `choices` (returned as given).
std::string json_choice(const nlohmann::json& v, const std::string& field, std::initializer_list<const char*> choices);
// An array of min..max items (413 beyond max).
const nlohmann::json& json_array(const nlohmann::json& v, const std::string& field, std::size_t min, std::size_t max);
// A string of at most max_bytes bytes.
const std::string& json_string(const nlohmann::json& v, const std::string& field, std::size_t max_bytes);

// --- query parameters ---
// A finite number in [min, max]; `fallback` when absent.
double query_number(const Request& req, const std::string& name, double min, double max, double fallback);
// One of `choices`; `fallback` when absent.
std::string query_choice(const Request& req, const std::string& name, std::initializer_list<const char*> choices,
                         const std::string& fallback);

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
