#pragma once
// Curators' rules that clean a metro network at import, so every reader gets clean names from
// the store: strip prefixes and suffixes ("U ", " (Berlin)"), drop bracketed parts ("[U8]"),
// title-case names written in capitals only ("PRAÇA DE ESPANHA" -> "Praça de Espanha"), rename
// single stations, hide lines (under construction), override a line's label or colour.
// Manifests and uploads carry them as JSON (load/metro_rules_json.hpp). Pure functions: no I/O.

#include "model/metro.hpp"

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tourmap::load {

struct LineOverride {
  std::string label;  // empty: keep the data's
  std::string color;  // "rrggbb" (a leading '#' is dropped); empty: keep the data's
  bool operator==(const LineOverride&) const = default;
};

struct MetroRules {
  // Patterns (load/text_pattern.hpp) stripped from the start / end of names, repeatedly, in any
  // order, as long as something is left: "S+U Wittenau (Berlin)" -> "Wittenau".
  std::vector<std::string> strip_prefixes;
  std::vector<std::string> strip_suffixes;
  // Bracket pairs whose bracketed parts (nesting included) are dropped: "()", "[]", "{}", "<>".
  std::vector<std::string> drop_brackets;
  // Names written in capitals only (no lower-case letter, two capitals or more) become Title
  // Case; words in `particles` stay lower case except at the start of the name.
  bool title_case = false;
  std::vector<std::string> particles;
  // Exact name -> name, for what the general rules cannot fix (a missing accent). Looked up on
  // the data's name and on each cleaned form; the new name is final, so the other rules must
  // leave it as it is (rules_error), or it must map to itself ({"ISCTE": "ISCTE"} keeps capitals).
  std::map<std::string, std::string> rename;
  // Patterns matched against each line's id and label (whole): matching lines are removed.
  std::vector<std::string> hide_lines;
  // Line id (as in the data) -> new label and/or colour.
  std::map<std::string, LineOverride> lines;
  // Lines whose colours differ by less than this CIEDE2000 difference get distinct styles
  // (metro/line_styles.hpp); unset: the default there. 0 turns the distinction off.
  std::optional<double> min_colour_difference;

  bool empty() const;
  bool operator==(const MetroRules&) const = default;
};

// Limits on what rules may hold: they come from uploads too, and each pattern is tried on
// every name.
inline constexpr std::size_t kMaxRulePatterns = 100;  // per list
inline constexpr std::size_t kMaxPatternBytes = 256;
inline constexpr std::size_t kMaxRenames = 10'000;
inline constexpr std::size_t kMaxRuleTextBytes = 1'024;  // names and labels

// Why the rules cannot be used, naming the field ("strip_prefixes[2]: ..."), or "" when valid.
std::string rules_error(const MetroRules& rules);

// The single steps, exposed for tests. Each leaves a name alone when it would become empty.
std::string collapse_spaces(std::string_view name);  // trims, and runs of blanks become one space
std::string drop_bracketed(std::string_view name, const std::vector<std::string>& pairs);
std::string strip_affixes(std::string_view name, const std::vector<std::string>& prefixes,
                          const std::vector<std::string>& suffixes);
bool is_all_caps(std::string_view name);
// Each word (a run of letters and digits) lower case with its first letter capitalised;
// `particles` (matched case-insensitively) all lower case unless first.
std::string title_case(std::string_view name, const std::vector<std::string>& particles);

// All name rules, repeated until nothing changes or a rename applies: cleaning a clean name
// (with valid rules) changes nothing.
std::string clean_name(std::string_view name, const MetroRules& rules);

// True when a hide_lines pattern matches the line's id or label.
bool line_hidden(const model::MetroLine& line, const MetroRules& rules);

struct RulesReport {
  std::size_t names_changed = 0;
  std::vector<std::string> hidden_lines;  // labels of the removed lines
  std::size_t removed_edges = 0;          // edges only hidden lines ran on
  std::size_t removed_stations = 0;       // stations (and junctions, below) left without an edge
  std::size_t removed_junctions = 0;
  std::size_t lines_overridden = 0;
};

// Applies the rules to the network: hides lines first (by the data's ids and labels), then
// overrides labels and colours, then cleans every node's name. A hidden line leaves every
// edge; an edge left without lines is removed, and so is a node that loses all its edges
// (nodes that had none in the data stay). Throws std::invalid_argument when `rules.lines`
// names a line the network does not have or when the rules hide every line; the rules must
// be valid (rules_error).
RulesReport apply_metro_rules(model::MetroNetwork& net, const MetroRules& rules);

}  // namespace tourmap::load
