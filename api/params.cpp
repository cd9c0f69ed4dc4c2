#include "params.hpp"

#include <charconv>
#include <cstdio>
#include <cmath>
#include <vector>

namespace tourmap::api {

ApiError bad(const std::string& field, const std::string& message, const std::string& code) {
  return ApiError(400, code, field + ": " + message, field);
}

ApiError too_large(const std::string& field, const std::string& message) {
  return ApiError(413, "too_large", field + ": " + message, field);
}

ApiError not_found(const std::string& field, const std::string& what, const std::string& id) {
  return ApiError(404, "not_found", field + ": no " + what + " '" + shown(id) + "'", field);
}

std::string shown(std::string_view text) {
  constexpr std::size_t kMax = 64;
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (text.size() > kMax) out += "...";
  return out;
}

const nlohmann::json* member(const nlohmann::json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

void reject_unknown(const nlohmann::json& object, const std::string& prefix, std::initializer_list<const char*> known) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    bool ok = false;
    for (auto k : known) ok = ok || it.key() == k;
    if (!ok) throw bad(prefix.empty() ? shown(it.key()) : prefix + "." + shown(it.key()), "unknown field");
  }
}

double json_number(const nlohmann::json& v, const std::string& field, double min, double max) {
  if (!v.is_number()) throw bad(field, "expected a number");
  const double d = v.get<double>();
  if (!std::isfinite(d) || d < min || d > max)
    throw bad(field, "must be between " + nlohmann::json(min).dump() + " and " + nlohmann::json(max).dump());
  return d;
}

long long json_integer(const nlohmann::json& v, const std::string& field, long long min, long long max) {
  if (!v.is_number_integer()) throw bad(field, "expected an integer");
  // An unsigned beyond long long's range reads as negative through get<long long>.
  if (v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(max))
    throw bad(field, "must be between " + std::to_string(min) + " and " + std::to_string(max));
  const auto i = v.get<long long>();
  if (i < min || i > max) throw bad(field, "must be between " + std::to_string(min) + " and " + std::to_string(max));
  return i;
}

bool json_bool(const nlohmann::json& v, const std::string& field) {
  if (!v.is_boolean()) throw bad(field, "expected true or false");
  return v.get<bool>();
}

namespace {

std::string list_of(std::initializer_list<const char*> choices) {
  std::string all;
  for (auto c : choices) all += (all.empty() ? "" : ", ") + std::string(c);
  return all;
}

std::string choice_of(const std::string& s, const std::string& field, std::initializer_list<const char*> choices) {
  for (auto c : choices)
    if (s == c) return s;
  throw bad(field, "'" + shown(s) + "' is not one of " + list_of(choices));
}

}  // namespace

std::string json_choice(const nlohmann::json& v, const std::string& field, std::initializer_list<const char*> choices) {
  if (!v.is_string()) throw bad(field, "expected one of " + list_of(choices));
  return choice_of(v.get_ref<const std::string&>(), field, choices);
}

const nlohmann::json& json_array(const nlohmann::json& v, const std::string& field, std::size_t min, std::size_t max) {
  if (!v.is_array()) throw bad(field, "expected an array");
  if (v.size() < min) throw bad(field, "needs at least " + std::to_string(min) + " item(s)");
  if (v.size() > max) throw too_large(field, "at most " + std::to_string(max) + " items");
  return v;
}

const std::string& json_string(const nlohmann::json& v, const std::string& field, std::size_t max_bytes) {
  if (!v.is_string()) throw bad(field, "expected a string");
  const auto& s = v.get_ref<const std::string&>();
  if (s.size() > max_bytes) throw too_large(field, "at most " + std::to_string(max_bytes) + " bytes");
  return s;
}

namespace {

double parse_double(const std::string& s, const std::string& field) {
  double v = 0.0;
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || ptr != s.data() + s.size())
    throw bad(field, "'" + shown(s) + "' is not a number");
  if (!std::isfinite(v)) throw bad(field, "numbers must be finite");
  return v;
}

geo::BBox make_bbox(const std::vector<double>& v, const std::string& field) {
  geo::BBox box{v[0], v[1], v[2], v[3]};
  if (box.min_lon < -180 || box.max_lon > 180 || box.min_lat < -90 || box.max_lat > 90)
    throw bad(field, "longitudes must be within [-180, 180] and latitudes within [-90, 90]");
  if (box.min_lon > box.max_lon || box.min_lat > box.max_lat)
    throw bad(field, "min must not exceed max (min_lon,min_lat,max_lon,max_lat)");
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
  if (v.size() != 4) throw bad(field, "expected 4 numbers min_lon,min_lat,max_lon,max_lat");
  return make_bbox(v, field);
}

geo::BBox parse_bbox_json(const nlohmann::json& value, const std::string& field) {
  if (!value.is_array() || value.size() != 4) throw bad(field, "expected an array of 4 numbers");
  std::vector<double> v;
  for (const auto& x : value) {
    if (!x.is_number()) throw bad(field, "expected numbers");
    double d = x.get<double>();
    if (!std::isfinite(d)) throw bad(field, "numbers must be finite");
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
    throw bad(name, "'" + shown(*text) + "' is not an integer");
  if (v < min || v > max) throw bad(name, "must be between " + std::to_string(min) + " and " + std::to_string(max));
  return v;
}

double query_number(const Request& req, const std::string& name, double min, double max, double fallback) {
  const auto* text = req.query_param(name);
  if (!text) return fallback;
  const double v = parse_double(*text, name);
  if (v < min || v > max)
    throw bad(name, "must be between " + nlohmann::json(min).dump() + " and " + nlohmann::json(max).dump());
  return v;
}

std::string query_choice(const Request& req, const std::string& name, std::initializer_list<const char*> choices,
                         const std::string& fallback) {
  const auto* text = req.query_param(name);
  return text ? choice_of(*text, name, choices) : fallback;
}

bool query_bool(const Request& req, const std::string& name, bool fallback) {
  const auto* text = req.query_param(name);
  if (!text) return fallback;
  if (*text == "true" || *text == "1" || text->empty()) return true;
  if (*text == "false" || *text == "0") return false;
  throw bad(name, "expected true or false");
}

void require_slug(const std::string& id, const std::string& what, const std::string& field) {
  bool ok = !id.empty() && id.size() <= 64;
  for (char c : id) ok = ok && ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_');
  if (!ok) throw not_found(field, what, id);
}

nlohmann::json parse_json_body(const Request& req) {
  auto semi = req.content_type.find(';');
  auto type = req.content_type.substr(0, semi);
  while (!type.empty() && type.back() == ' ') type.pop_back();
  if (type != "application/json" && type != "application/geo+json")
    throw ApiError(415, "unsupported_media_type", "Content-Type: send the body as application/json", "Content-Type");
  // Depth cap: nesting beyond any real GeoJSON is refused before it costs stack or memory.
  constexpr int kMaxDepth = 64;
  bool too_deep = false;
  auto limit_depth = [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
    if (depth > kMaxDepth) too_deep = true;
    return !too_deep;
  };
  try {
    auto doc = nlohmann::json::parse(req.body, limit_depth);
    if (too_deep) throw bad("body", "nests deeper than 64 levels", "invalid_json");
    return doc;
  } catch (const nlohmann::json::parse_error& e) {
    throw bad("body", "not valid JSON (at byte " + std::to_string(e.byte) + ")", "invalid_json");
  } catch (const nlohmann::json::out_of_range&) {
    // The parser reports a number beyond double's range (e.g. 1e309) as out_of_range 406.
    throw bad("body", "holds a number too large for a double", "invalid_json");
  }
}

}  // namespace tourmap::api
