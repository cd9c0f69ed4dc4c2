#include "load/name_rules.hpp"

#include "load/text_pattern.hpp"
#include "load/text_repair.hpp"
#include "load/utf8.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tourmap::load {
namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

std::string trimmed(std::string_view s) {
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return std::string(s);
}

// Letters and digits make words; combining accents (U+0300..U+036F) stay with their letter.
bool word_char(std::uint32_t cp) {
  return is_upper(cp) || is_lower(cp) || (cp >= '0' && cp <= '9') || (cp >= 0x0300 && cp <= 0x036F);
}

bool hex_colour(std::string_view c) {
  if (!c.empty() && c[0] == '#') c.remove_prefix(1);
  return c.size() == 6 && std::all_of(c.begin(), c.end(), [](char ch) {
           return (ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'f') || (ch >= 'A' && ch <= 'F');
         });
}

std::string text_error(std::string_view text, std::size_t max_bytes) {
  if (text.empty()) return "empty";
  if (text.size() > max_bytes) return "longer than " + std::to_string(max_bytes) + " bytes";
  if (!is_valid_utf8(text)) return "not valid UTF-8";
  return "";
}

std::string patterns_error(const std::vector<std::string>& patterns, const std::string& field) {
  if (patterns.size() > kMaxRulePatterns)
    return field + ": more than " + std::to_string(kMaxRulePatterns) + " patterns";
  for (std::size_t i = 0; i < patterns.size(); ++i) {
    auto why = patterns[i].size() > kMaxPatternBytes ? "longer than " + std::to_string(kMaxPatternBytes) + " bytes"
                                                      : pattern_error(patterns[i]);
    if (!why.empty()) return field + "[" + std::to_string(i) + "]: '" + patterns[i] + "' " + why;
  }
  return "";
}

// The general rules, one step each; clean_name applies them in turn until nothing changes.
std::string clean_step(int step, const std::string& name, const MetroRules& rules) {
  switch (step) {
    case 0: return drop_bracketed(name, rules.drop_brackets);
    case 1: return strip_affixes(name, rules.strip_prefixes, rules.strip_suffixes);
    default: return rules.title_case && is_all_caps(name) ? title_case(name, rules.particles) : name;
  }
}

}  // namespace

bool MetroRules::empty() const { return *this == MetroRules{}; }

std::string rules_error(const MetroRules& rules) {
  for (auto [list, field] : {std::pair{&rules.strip_prefixes, "strip_prefixes"},
                             std::pair{&rules.strip_suffixes, "strip_suffixes"},
                             std::pair{&rules.hide_lines, "hide_lines"}})
    if (auto why = patterns_error(*list, field); !why.empty()) return why;
  for (std::size_t i = 0; i < rules.drop_brackets.size(); ++i) {
    const auto& pair = rules.drop_brackets[i];
    if (pair != "()" && pair != "[]" && pair != "{}" && pair != "<>")
      return "drop_brackets[" + std::to_string(i) + "]: '" + pair + "' is not one of \"()\", \"[]\", \"{}\", \"<>\"";
  }
  if (rules.particles.size() > kMaxRulePatterns)
    return "particles: more than " + std::to_string(kMaxRulePatterns) + " words";
  for (std::size_t i = 0; i < rules.particles.size(); ++i) {
    const auto& word = rules.particles[i];
    auto why = text_error(word, 64);
    if (why.empty() && std::any_of(word.begin(), word.end(), blank)) why = "is more than one word";
    if (!why.empty()) return "particles[" + std::to_string(i) + "]: '" + word + "' " + why;
  }
  if (rules.rename.size() > kMaxRenames) return "rename: more than " + std::to_string(kMaxRenames) + " names";
  for (const auto& [from, to] : rules.rename) {
    if (auto why = text_error(from, kMaxRuleTextBytes); !why.empty()) return "rename: a name is " + why;
    if (auto why = text_error(to, kMaxRuleTextBytes); !why.empty()) return "rename['" + from + "']: " + why;
    if (rules.rename.count(to)) {
      if (to != from) return "rename['" + from + "']: '" + to + "' is renamed itself (rename to the final name)";
      continue;  // kept as it is, whatever the other rules would do
    }
    // A new name is final: the other rules must leave it alone, or cleaning a clean name
    // would change it.
    if (auto again = clean_name(to, rules); again != to)
      return "rename['" + from + "']: the other rules would change '" + to + "' to '" + again +
             "' (rename to that, or map '" + to + "' to itself to keep it)";
  }
  for (const auto& [id, o] : rules.lines) {
    if (id.empty()) return "lines: an empty line id";
    const std::string field = "lines['" + id + "']";
    if (o.label.empty() && o.color.empty()) return field + ": give a label, a color or both";
    if (!o.label.empty())
      if (auto why = text_error(o.label, kMaxRuleTextBytes); !why.empty()) return field + ".label: " + why;
    if (!o.color.empty() && !hex_colour(o.color))
      return field + ".color: '" + o.color + "' is not a colour like \"00782a\" or \"#00782A\"";
  }
  if (auto d = rules.min_colour_difference; d && !(std::isfinite(*d) && *d >= 0 && *d <= 100))
    return "min_colour_difference: expected a number from 0 to 100 (CIEDE2000)";
  return "";
}

std::string collapse_spaces(std::string_view name) {
  std::string out;
  out.reserve(name.size());
  for (char c : name) {
    if (blank(c)) {
      if (!out.empty() && out.back() != ' ') out.push_back(' ');
    } else {
      out.push_back(c);
    }
  }
  if (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string drop_bracketed(std::string_view name, const std::vector<std::string>& pairs) {
  std::string s(name);
  for (const auto& pair : pairs) {
    if (pair.size() != 2) continue;
    std::string out;
    std::size_t depth = 0, open_at = 0;
    // ASCII brackets: a byte scan never splits a UTF-8 character.
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s[i] == pair[0]) {
        if (depth++ == 0) open_at = i;
      } else if (s[i] == pair[1] && depth > 0) {
        --depth;
      } else if (depth == 0) {
        out.push_back(s[i]);
      }
    }
    if (depth > 0) out += s.substr(open_at);  // never closed: not a bracketed part
    s = collapse_spaces(out);
  }
  s = collapse_spaces(s);
  return s.empty() ? std::string(name) : s;
}

std::string strip_affixes(std::string_view name, const std::vector<std::string>& prefixes,
                          const std::vector<std::string>& suffixes) {
  std::string s = trimmed(name);
  // Every strip shortens the name, so this ends.
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& p : prefixes) {
      if (auto k = shortest_prefix_match(p, s); k > 0) {
        auto rest = trimmed(std::string_view(s).substr(k));
        if (!rest.empty()) s = std::move(rest), changed = true;
      }
    }
    for (const auto& p : suffixes) {
      if (auto k = shortest_suffix_match(p, s); k > 0) {
        auto rest = trimmed(std::string_view(s).substr(0, s.size() - k));
        if (!rest.empty()) s = std::move(rest), changed = true;
      }
    }
  }
  return s;
}

bool is_all_caps(std::string_view name) {
  std::size_t upper = 0;
  for (std::size_t i = 0; i < name.size();) {
    auto cp = decode_utf8(name, i);
    if (!cp || is_lower(*cp)) return false;
    upper += is_upper(*cp) ? 1 : 0;
  }
  return upper >= 2;
}

std::string title_case(std::string_view name, const std::vector<std::string>& particles) {
  std::vector<std::string> lower_particles;
  for (const auto& p : particles) lower_particles.push_back(lower_utf8(p));
  std::string out;
  std::vector<std::uint32_t> word;
  bool first_word = true;
  auto flush = [&] {
    if (word.empty()) return;
    std::string lowered;
    for (auto cp : word) append_utf8(lowered, to_lower(cp));
    bool particle = !first_word &&
                    std::find(lower_particles.begin(), lower_particles.end(), lowered) != lower_particles.end();
    if (!particle) {
      lowered.clear();
      for (std::size_t k = 0; k < word.size(); ++k) append_utf8(lowered, k == 0 ? to_upper(word[k]) : to_lower(word[k]));
    }
    out += lowered;
    word.clear();
    first_word = false;
  };
  for (std::size_t i = 0; i < name.size();) {
    auto cp = decode_utf8(name, i);
    if (!cp) return std::string(name);
    if (word_char(*cp)) {
      word.push_back(*cp);
    } else {
      flush();
      append_utf8(out, *cp);
    }
  }
  flush();
  return out;
}

std::string clean_name(std::string_view name, const MetroRules& rules) {
  std::string s = collapse_spaces(name);
  // Rounds of the steps until nothing changes, so the result is clean: each round shortens the
  // name or title-cases it (once), so a few suffice. A rename ends it: the data's name and every
  // form between two steps are looked up, and the new name is final (rules_error checks that
  // it is clean).
  for (int round = 0; round < 64; ++round) {
    const std::string start = s;
    for (int step = 0; step < 3; ++step) {
      if (auto it = rules.rename.find(s); it != rules.rename.end()) return collapse_spaces(it->second);
      s = clean_step(step, s, rules);
    }
    if (s == start) break;
  }
  if (auto it = rules.rename.find(s); it != rules.rename.end()) return collapse_spaces(it->second);
  return s;
}

bool line_hidden(const model::MetroLine& line, const MetroRules& rules) {
  return std::any_of(rules.hide_lines.begin(), rules.hide_lines.end(), [&](const std::string& p) {
    return pattern_matches(p, line.id) || pattern_matches(p, line.label);
  });
}

RulesReport apply_metro_rules(model::MetroNetwork& net, const MetroRules& rules) {
  RulesReport report;
  for (const auto& entry : rules.lines) {
    const auto& id = entry.first;
    if (std::none_of(net.lines.begin(), net.lines.end(), [&](const model::MetroLine& l) { return l.id == id; }))
      throw std::invalid_argument("rules.lines: the network has no line with id '" + id + "'");
  }

  // Hide lines: new line indices, then edges without a line left, then nodes without an edge left.
  std::vector<std::int64_t> line_map(net.lines.size(), -1);
  std::vector<model::MetroLine> lines;
  for (std::size_t l = 0; l < net.lines.size(); ++l) {
    if (line_hidden(net.lines[l], rules)) {
      report.hidden_lines.push_back(net.lines[l].label);
      continue;
    }
    line_map[l] = static_cast<std::int64_t>(lines.size());
    lines.push_back(net.lines[l]);
  }
  if (lines.empty() && !net.lines.empty()) throw std::invalid_argument("rules.hide_lines: every line would be hidden");
  if (!report.hidden_lines.empty()) {
    std::vector<char> had_edge(net.nodes.size(), 0), has_edge(net.nodes.size(), 0);
    std::vector<model::MetroEdge> edges;
    for (auto& e : net.edges) {
      had_edge[e.from] = had_edge[e.to] = 1;
      std::vector<std::uint32_t> kept;
      for (auto l : e.lines)
        if (line_map[l] >= 0) kept.push_back(static_cast<std::uint32_t>(line_map[l]));
      // An edge that carried no line in the data is track, not a hidden line's: it stays.
      if (kept.empty() && !e.lines.empty()) {
        ++report.removed_edges;
        continue;
      }
      e.lines = std::move(kept);
      has_edge[e.from] = has_edge[e.to] = 1;
      edges.push_back(std::move(e));
    }
    std::vector<std::uint32_t> node_map(net.nodes.size(), 0);
    std::vector<model::MetroNode> nodes;
    for (std::size_t v = 0; v < net.nodes.size(); ++v) {
      if (had_edge[v] && !has_edge[v]) {
        ++(net.nodes[v].is_station() ? report.removed_stations : report.removed_junctions);
        continue;
      }
      node_map[v] = static_cast<std::uint32_t>(nodes.size());
      nodes.push_back(std::move(net.nodes[v]));
    }
    for (auto& e : edges) {
      e.from = node_map[e.from];
      e.to = node_map[e.to];
    }
    net.nodes = std::move(nodes);
    net.edges = std::move(edges);
  }
  net.lines = std::move(lines);

  for (auto& line : net.lines) {
    auto it = rules.lines.find(line.id);
    if (it == rules.lines.end()) continue;
    if (!it->second.label.empty()) line.label = it->second.label;
    if (!it->second.color.empty()) line.color = it->second.color[0] == '#' ? it->second.color.substr(1) : it->second.color;
    ++report.lines_overridden;
  }

  for (auto& node : net.nodes) {
    if (node.name.empty()) continue;
    auto clean = clean_name(node.name, rules);
    if (clean != node.name) {
      node.name = std::move(clean);
      ++report.names_changed;
    }
  }
  return report;
}

}  // namespace tourmap::load
