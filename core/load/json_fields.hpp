#pragma once
// Small accessors for loosely typed JSON inputs (GeoJSON properties from many sources).

#include "load/import_limits.hpp"

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace tourmap::load {

// A string or number as text (ids are either in the wild); nullopt when absent/null/other.
std::optional<std::string> json_text(const nlohmann::json& obj, std::string_view key);
// First present key among `keys`, matched case-insensitively.
std::optional<std::string> json_text_any(const nlohmann::json& obj, std::span<const std::string_view> keys);
// A finite number, or a string holding one; nullopt otherwise.
std::optional<double> json_number_any(const nlohmann::json& obj, std::span<const std::string_view> keys);

// Parses JSON, turning syntax errors into LoadError with the byte offset. Counts the values while
// parsing: beyond limits.max_json_values it stops with LimitExceeded (the document is never
// built whole); polls util::check_stop() at the first value and every 65,536.
nlohmann::json parse_json(std::string_view text, const std::string& source, const ImportLimits& limits = {});

}  // namespace tourmap::load
