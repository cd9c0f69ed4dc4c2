#include "load/json_fields.hpp"

#include "load/load_error.hpp"
#include "load/strings.hpp"
#include "util/stop.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

namespace tourmap::load {
namespace {

const nlohmann::json* find_key(const nlohmann::json& obj, std::string_view key) {
  if (!obj.is_object()) return nullptr;
  auto exact = obj.find(std::string(key));
  if (exact != obj.end()) return &*exact;
  for (auto it = obj.begin(); it != obj.end(); ++it)
    if (iequals(it.key(), key)) return &*it;
  return nullptr;
}

std::optional<std::string> as_text(const nlohmann::json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number_unsigned()) return std::to_string(v.get<unsigned long long>());
  if (v.is_number_float()) {
    double d = v.get<double>();
    if (std::isfinite(d) && d == std::floor(d) && std::fabs(d) < 1e15) return std::to_string(static_cast<long long>(d));
    return v.dump();
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> json_text(const nlohmann::json& obj, std::string_view key) {
  if (const auto* v = find_key(obj, key)) return as_text(*v);
  return std::nullopt;
}

std::optional<std::string> json_text_any(const nlohmann::json& obj, std::span<const std::string_view> keys) {
  for (auto key : keys)
    if (auto v = json_text(obj, key); v && !v->empty()) return v;
  return std::nullopt;
}

std::optional<double> json_number_any(const nlohmann::json& obj, std::span<const std::string_view> keys) {
  for (auto key : keys) {
    const auto* v = find_key(obj, key);
    if (!v) continue;
    if (v->is_number()) {
      double d = v->get<double>();
      if (std::isfinite(d)) return d;
    } else if (v->is_string()) {
      const auto& s = v->get_ref<const std::string&>();
      double d = 0.0;
      auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), d);
      if (!s.empty() && ec == std::errc() && ptr == s.data() + s.size() && std::isfinite(d)) return d;
    }
  }
  return std::nullopt;
}

nlohmann::json parse_json(std::string_view text, const std::string& source, const ImportLimits& limits) {
  std::size_t values = 0;
  const std::size_t max_values = limits.max_json_values;
  // Called for every value and at the start of every object and array (and for keys and ends,
  // which are not counted). Throwing from it ends the parse; nlohmann passes it through.
  const nlohmann::json::parser_callback_t count = [&](int, nlohmann::json::parse_event_t event, nlohmann::json&) {
    using E = nlohmann::json::parse_event_t;
    if (event == E::value || event == E::object_start || event == E::array_start) {
      if (++values > max_values)
        check_limit(values, max_values, "max_json_values", source, "JSON values");
      if ((values & 0xffff) == 1) util::check_stop();  // the first value, then every 65,536
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, count);
  } catch (const nlohmann::json::parse_error& e) {
    throw LoadError(source + " byte " + std::to_string(e.byte), "invalid JSON");
  } catch (const nlohmann::json::out_of_range&) {
    // The parser reports a number beyond double's range (e.g. 1e309) as out_of_range 406.
    throw LoadError(source, "invalid JSON: a number is too large for a double");
  }
}

}  // namespace tourmap::load
