#pragma once
// The JSON form of a city's metro rules (load/name_rules.hpp), as manifests and uploads carry
// them in "rules":
//
//   {"strip_prefixes": ["Berlin, ", "S+U ", "U "], "strip_suffixes": [" (Berlin)", " U#"],
//    "drop_brackets": ["[]"], "title_case": true, "particles": ["de", "do"],
//    "rename": {"CAIS DO SODRE": "Cais do Sodré"}, "hide_lines": ["*bau"],
//    "lines": {"4": {"color": "00782A", "label": "District"}}, "min_colour_difference": 10}
//
// Every field is optional; an unknown field is an error (a misspelt rule would otherwise do
// nothing without a word).

#include "load/name_rules.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace tourmap::load {

// Parses and validates the rules; throws std::invalid_argument naming `where` and the field
// ("cities[berlin].metro.rules.strip_prefixes[1]: ...").
MetroRules parse_metro_rules(const nlohmann::json& rules, const std::string& where);

// The canonical JSON of the rules (only the fields set, keys sorted): equal rules give equal
// text, and parse_metro_rules reads it back.
nlohmann::json metro_rules_json(const MetroRules& rules);

}  // namespace tourmap::load
