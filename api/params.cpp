#include "params.hpp"

#include <charconv>
#include <cmath>
#include <vector>

namespace tourmap::api {
namespace {

ApiError bad(const std::string& field, const std::string& message) {
  return ApiError(400, "invalid_parameter", message, field);
}

double parse_double(const std::string& s, const std::string& field) {
  double v = 0.0;
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || ptr != s.data() + s.size())
    throw bad(field, field + ": '" + s + "' is not a number");
  if (!std::isfinite(v)) throw bad(field, field + ": numbers must be finite");
  return v;
}

geo::BBox make_bbox(const std::vector<double>& v, const std::string& field) {
  geo::BBox box{v[0], v[1], v[2], v[3]};
  if (box.min_lon < -180 || box.max_lon > 180 || box.min_lat < -90 || box.max_lat > 90)
    throw bad(field, field + ": longitudes must be within [-180, 180] and latitudes within [-90, 90]");
  if (box.min_lon > box.max_lon || box.min_lat > box.max_lat)
    throw bad(field, field + ": min must not exceed max (min_lon,min_lat,max_lon,max_lat)");
  return box;
}

}  // namespace

geo::BBox parse_bbox(const std::string& text, const std::string& field) {
  std::vector<double> v;
  std::size_t start = 0;
  while (true) {
    auto comma = text.find(',', start);
    v.push_back(parse_double(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start), field));
    if (comma == std::string::npos) break;
    start = comma + 1;
    if (v.size() > 4) break;
  }
  if (v.size() != 4) throw bad(field, field + ": expected 4 numbers min_lon,min_lat,max_lon,max_lat");
  return make_bbox(v, field);
}

geo::BBox parse_bbox_json(const nlohmann::json& value, const std::string& field) {
  if (!value.is_array() || value.size() != 4) throw bad(field, field + ": expected an array of 4 numbers");
  std::vector<double> v;
  for (const auto& x : value) {
    if (!x.is_number()) throw bad(field, field + ": expected numbers");
    double d = x.get<double>();
    if (!std::isfinite(d)) throw bad(field, field + ": numbers must be finite");
    v.push_back(d);
  }
  return make_bbox(v, field);
}

std::optional<geo::BBox> query_bbox(const Request& req, const std::string& name) {
  const auto* text = req.query_param(name);
  if (!text) return std::nullopt;
  return parse_bbox(*text, name);
}

long long query_int(const Request& req, const std::string& name, long long min, long long max, long long fallback) {
  const auto* text = req.query_param(name);
  if (!text) return fallback;
  long long v = 0;
  auto [ptr, ec] = std::from_chars(text->data(), text->data() + text->size(), v);
  if (text->empty() || ec != std::errc() || ptr != text->data() + text->size())
    throw bad(name, name + ": '" + *text + "' is not an integer");
  if (v < min || v > max)
    throw bad(name, name + ": must be between " + std::to_string(min) + " and " + std::to_string(max));
  return v;
}

bool query_bool(const Request& req, const std::string& name, bool fallback) {
  const auto* text = req.query_param(name);
  if (!text) return fallback;
  if (*text == "true" || *text == "1" || text->empty()) return true;
  if (*text == "false" || *text == "0") return false;
  throw bad(name, name + ": expected true or false");
}

void require_slug(const std::string& id, const std::string& what, const std::string& field) {
  bool ok = !id.empty() && id.size() <= 64;
  for (char c : id) ok = ok && ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_');
  if (!ok) throw ApiError(404, "not_found", "no " + what + " '" + id + "'", field);
}

nlohmann::json parse_json_body(const Request& req) {
  auto semi = req.content_type.find(';');
  auto type = req.content_type.substr(0, semi);
  while (!type.empty() && type.back() == ' ') type.pop_back();
  if (type != "application/json" && type != "application/geo+json")
    throw ApiError(415, "unsupported_media_type", "send the body as application/json", "Content-Type");
  // Depth cap: nesting beyond any real GeoJSON is refused before it costs stack or memory.
  constexpr int kMaxDepth = 64;
  bool too_deep = false;
  auto limit_depth = [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
    if (depth > kMaxDepth) too_deep = true;
    return !too_deep;
  };
  try {
    auto doc = nlohmann::json::parse(req.body, limit_depth);
    if (too_deep) throw ApiError(400, "invalid_json", "body nests deeper than 64 levels", "body");
    return doc;
  } catch (const nlohmann::json::parse_error& e) {
    throw ApiError(400, "invalid_json", "body is not valid JSON (at byte " + std::to_string(e.byte) + ")", "body");
  } catch (const nlohmann::json::out_of_range&) {
    // The parser reports a number beyond double's range (e.g. 1e309) as out_of_range 406.
    throw ApiError(400, "invalid_json", "body holds a number too large for a double", "body");
  }
}

}  // namespace tourmap::api
