#include "load/metro_rules_json.hpp"

#include <stdexcept>

namespace tourmap::load {
namespace {

constexpr const char* kFields[] = {"strip_prefixes", "strip_suffixes", "drop_brackets", "title_case", "particles",
                                   "rename",         "hide_lines",     "lines",         "min_colour_difference"};

std::invalid_argument error(const std::string& where, const std::string& what) {
  return std::invalid_argument(where + ": " + what);
}

std::vector<std::string> strings(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array()) throw error(where, "expected an array of strings");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_string()) throw error(where + "[" + std::to_string(i) + "]", "expected a string");
    out.push_back(j[i].get<std::string>());
  }
  return out;
}

std::string text(const nlohmann::json& j, const std::string& where) {
  if (!j.is_string()) throw error(where, "expected a string");
  auto s = j.get<std::string>();
  if (s.empty()) throw error(where, "empty");
  return s;
}

load::LineOverride line_override(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw error(where, "expected an object with \"label\" and/or \"color\"");
  load::LineOverride o;
  for (const auto& [key, value] : j.items()) {
    if (key == "label") o.label = text(value, where + ".label");
    else if (key == "color") o.color = text(value, where + ".color");
    else throw error(where, "unknown field '" + key + "' (expected label, color)");
  }
  return o;
}

}  // namespace

load::MetroRules parse_metro_rules(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw error(where, "expected an object");
  load::MetroRules r;
  for (const auto& [key, value] : j.items()) {
    const std::string at = where + "." + key;
    if (key == "strip_prefixes") r.strip_prefixes = strings(value, at);
    else if (key == "strip_suffixes") r.strip_suffixes = strings(value, at);
    else if (key == "drop_brackets") r.drop_brackets = strings(value, at);
    else if (key == "particles") r.particles = strings(value, at);
    else if (key == "hide_lines") r.hide_lines = strings(value, at);
    else if (key == "title_case") {
      if (!value.is_boolean()) throw error(at, "expected true or false");
      r.title_case = value.get<bool>();
    } else if (key == "rename") {
      if (!value.is_object()) throw error(at, "expected an object of names");
      for (const auto& [from, to] : value.items()) r.rename[from] = text(to, at + "['" + from + "']");
    } else if (key == "lines") {
      if (!value.is_object()) throw error(at, "expected an object of line ids");
      for (const auto& [id, o] : value.items()) r.lines[id] = line_override(o, at + "['" + id + "']");
    } else if (key == "min_colour_difference") {
      if (!value.is_number()) throw error(at, "expected a number");
      r.min_colour_difference = value.get<double>();
    } else {
      std::string known;
      for (const char* f : kFields) known += (known.empty() ? "" : ", ") + std::string(f);
      throw error(where, "unknown field '" + key + "' (expected " + known + ")");
    }
  }
  // rules_error names the field first ("strip_prefixes[1]: ..."): under `where` it reads as a path.
  if (auto why = load::rules_error(r); !why.empty()) throw std::invalid_argument(where + "." + why);
  return r;
}

nlohmann::json metro_rules_json(const load::MetroRules& r) {
  nlohmann::json j = nlohmann::json::object();
  auto list = [&](const char* key, const std::vector<std::string>& v) {
    if (!v.empty()) j[key] = v;
  };
  list("strip_prefixes", r.strip_prefixes);
  list("strip_suffixes", r.strip_suffixes);
  list("drop_brackets", r.drop_brackets);
  list("particles", r.particles);
  list("hide_lines", r.hide_lines);
  if (r.title_case) j["title_case"] = true;
  if (!r.rename.empty()) j["rename"] = r.rename;
  for (const auto& [id, o] : r.lines) {
    nlohmann::json line = nlohmann::json::object();
    if (!o.label.empty()) line["label"] = o.label;
    if (!o.color.empty()) line["color"] = o.color;
    j["lines"][id] = std::move(line);
  }
  if (r.min_colour_difference) j["min_colour_difference"] = *r.min_colour_difference;
  return j;
}

}  // namespace tourmap::load
