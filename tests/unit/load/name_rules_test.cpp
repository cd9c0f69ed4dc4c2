#include "load/name_rules.hpp"

#include "load/metro_load.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

namespace tourmap::load {
namespace {

// Berlin's rules as the sample manifest has them.
MetroRules berlin_rules() {
  MetroRules r;
  r.drop_brackets = {"[]"};
  r.strip_prefixes = {"Berlin, ", "S+U ", "U "};
  r.strip_suffixes = {" (Berlin)", " (Bln)", " Bhf", " U#"};
  r.rename = {{"Berlin Hauptbahnhof", "Hauptbahnhof"}};
  r.hide_lines = {"*bau"};
  return r;
}

MetroRules lisbon_rules() {
  MetroRules r;
  r.title_case = true;
  r.particles = {"de", "do", "da", "dos", "das", "e"};
  return r;
}

TEST(NameRules, StripsPrefixesAndSuffixes) {
  const std::vector<std::string> prefixes = {"Berlin, ", "S+U ", "U "};
  const std::vector<std::string> suffixes = {" (Berlin)", " (Bln)", " U#"};
  EXPECT_EQ(strip_affixes("U Alt-Tegel (Berlin)", prefixes, suffixes), "Alt-Tegel");
  EXPECT_EQ(strip_affixes("S+U Potsdamer Platz (Bln)", prefixes, suffixes), "Potsdamer Platz");
  // Both prefixes, in either order of the list: stripping repeats until none applies.
  EXPECT_EQ(strip_affixes("Berlin, U Stadtmitte U2", prefixes, suffixes), "Stadtmitte");
  EXPECT_EQ(strip_affixes("Berlin, U Stadtmitte U2", {"U ", "Berlin, "}, suffixes), "Stadtmitte");
  EXPECT_EQ(strip_affixes("Ullsteinstr.", prefixes, suffixes), "Ullsteinstr.");  // "U " needs the space
  // A strip that would leave nothing is not made.
  EXPECT_EQ(strip_affixes("U ", {"U"}, {}), "U");
  EXPECT_EQ(strip_affixes("(Berlin)", {}, {"(Berlin)"}), "(Berlin)");
}

TEST(NameRules, DropsBracketedParts) {
  EXPECT_EQ(drop_bracketed("S+U Wittenau (Berlin) [U8]", {"[]"}), "S+U Wittenau (Berlin)");
  EXPECT_EQ(drop_bracketed("Addison (Blue)", {"()"}), "Addison");
  EXPECT_EQ(drop_bracketed("Harlem (Blue - O'Hare Branch)", {"()"}), "Harlem");
  EXPECT_EQ(drop_bracketed("A [x] B [y]", {"[]"}), "A B");
  EXPECT_EQ(drop_bracketed("A (x (y) z) B", {"()"}), "A B");  // nested
  EXPECT_EQ(drop_bracketed("A (open", {"()"}), "A (open");    // never closed: kept
  EXPECT_EQ(drop_bracketed("A) B", {"()"}), "A) B");
  EXPECT_EQ(drop_bracketed("Kienberg (G\xC3\xA4rten der Welt)", {"[]"}), "Kienberg (G\xC3\xA4rten der Welt)");
  EXPECT_EQ(drop_bracketed("[U5]", {"[]"}), "[U5]");  // would leave nothing
}

TEST(NameRules, TitleCasesAllCapsNames) {
  const std::vector<std::string> particles = {"de", "do", "da", "dos", "das", "e"};
  EXPECT_EQ(title_case("PRA\xC3\x87" "A DE ESPANHA", particles), "Pra\xC3\xA7" "a de Espanha");  // PRAÇA
  EXPECT_EQ(title_case("S\xC3\x83O SEBASTI\xC3\x83O", particles), "S\xC3\xA3o Sebasti\xC3\xA3o");  // SÃO SEBASTIÃO
  EXPECT_EQ(title_case("MARQU\xC3\x8AS DE POMBAL", particles), "Marqu\xC3\xAAs de Pombal");       // MARQUÊS
  EXPECT_EQ(title_case("COL\xC3\x89GIO MILITAR-LUZ", particles), "Col\xC3\xA9gio Militar-Luz");     // hyphen starts a word
  EXPECT_EQ(title_case("ALTO DOS MOINHOS", particles), "Alto dos Moinhos");
  EXPECT_EQ(title_case("SR. ROUBADO", particles), "Sr. Roubado");
  EXPECT_EQ(title_case("DE ALTO E BAIXO", particles), "De Alto e Baixo");  // a particle first is capitalised
  EXPECT_EQ(title_case("RUA 1ST", {}), "Rua 1st");
  EXPECT_EQ(title_case("ŁÓDŹ FABRYCZNA", {}), "\xC5\x81\xC3\xB3" "d\xC5\xBA Fabryczna");  // Łódź
}

TEST(NameRules, OnlyAllCapsNamesAreAllCaps) {
  EXPECT_TRUE(is_all_caps("REBOLEIRA"));
  EXPECT_TRUE(is_all_caps("S\xC3\x83O SEBASTI\xC3\x83O"));
  EXPECT_TRUE(is_all_caps("SR. ROUBADO"));
  EXPECT_FALSE(is_all_caps("Arroios"));
  EXPECT_FALSE(is_all_caps("UIC-Halsted"));
  EXPECT_FALSE(is_all_caps("Praça de ESPANHA"));
  EXPECT_FALSE(is_all_caps("A"));    // one capital is not a shouted name
  EXPECT_FALSE(is_all_caps("18th"));
}

TEST(NameRules, CleanNameAppliesEveryRule) {
  auto berlin = berlin_rules();
  EXPECT_EQ(clean_name("U Alt-Tegel (Berlin)", berlin), "Alt-Tegel");
  EXPECT_EQ(clean_name("S+U Wittenau (Berlin) [U8]", berlin), "Wittenau");
  EXPECT_EQ(clean_name("S+U Potsdamer Platz (Bln) [U2]", berlin), "Potsdamer Platz");
  EXPECT_EQ(clean_name("S+U Friedrichstr. Bhf (Berlin)", berlin), "Friedrichstr.");
  EXPECT_EQ(clean_name("U Freie Universit\xC3\xA4t (Thielplatz) (Berlin)", berlin), "Freie Universit\xC3\xA4t (Thielplatz)");
  EXPECT_EQ(clean_name("S+U Berlin Hauptbahnhof", berlin), "Hauptbahnhof");  // renamed once cleaned
  EXPECT_EQ(clean_name("  Mehringdamm   Nord ", berlin), "Mehringdamm Nord");
  auto lisbon = lisbon_rules();
  lisbon.rename = {{"CAIS DO SODRE", "Cais do Sodr\xC3\xA9"}, {"Sr. Roubado", "Senhor Roubado"}};
  EXPECT_EQ(clean_name("CAIS DO SODRE", lisbon), "Cais do Sodr\xC3\xA9");  // the data's name
  EXPECT_EQ(clean_name("SR. ROUBADO", lisbon), "Senhor Roubado");          // the cleaned name
  EXPECT_EQ(clean_name("Arroios", lisbon), "Arroios");
}

TEST(NameRules, CleaningIsIdempotentOnTheSharedData) {
  auto check = [](const model::MetroNetwork& net, const MetroRules& rules) {
    for (const auto& node : net.nodes) {
      auto once = clean_name(node.name, rules);
      EXPECT_EQ(clean_name(once, rules), once) << node.name;
    }
  };
  check(load_metro_loom(test::data_file("metro/loom_berlin.json")), berlin_rules());
  check(load_metro_line_csv(test::data_file("metro/lisbon_metro_stations_metrodroid.csv")), lisbon_rules());
}

TEST(NameRules, RenamesAreFinal) {
  MetroRules r;
  r.title_case = true;
  r.strip_prefixes = {"U "};
  r.rename = {{"ISCTE", "ISCTE"}, {"U X", "Xanten"}};
  EXPECT_EQ(rules_error(r), "");
  EXPECT_EQ(clean_name("ISCTE", r), "ISCTE");   // kept in capitals
  EXPECT_EQ(clean_name("U ISCTE", r), "ISCTE");  // a cleaned form is looked up too
  EXPECT_EQ(clean_name("U X", r), "Xanten");
  EXPECT_EQ(clean_name("U ALTO", r), "Alto");
  // "U Foo" cleans to "Foo", which is renamed back to "U Foo": stable, so accepted.
  r.rename = {{"Foo", "U Foo"}};
  EXPECT_EQ(rules_error(r), "");
  EXPECT_EQ(clean_name("U Foo", r), "U Foo");
  // A new name the other rules would change is refused: cleaning it again would not keep it.
  r.rename = {{"X", "U Y"}};
  EXPECT_EQ(rules_error(r).rfind("rename['X']: the other rules would change 'U Y' to 'Y'", 0), 0u) << rules_error(r);
  r.rename = {{"X", "ALTO"}};
  EXPECT_EQ(rules_error(r).rfind("rename['X']: the other rules would change 'ALTO' to 'Alto'", 0), 0u) << rules_error(r);
}

// a - b - c - d on line "U1" (a-b-c) and "U1bau" (b-c, c-d), plus an isolated station e.
model::MetroNetwork small_network() {
  model::MetroNetwork net;
  for (const char* id : {"a", "b", "c", "d", "e"})
    net.nodes.push_back({id, id, std::string("U ") + id + " (Berlin)", {13.4, 52.5}});
  net.nodes.push_back({"j", "", "", {13.41, 52.5}});  // a junction only the construction line uses
  net.lines = {{"l1", "U1", "62ad2d"}, {"l2", "U1bau", "c2a18f"}};
  net.edges = {{0, 1, {0}, {}}, {1, 2, {0, 1}, {}}, {2, 5, {1}, {}}, {5, 3, {1}, {}}};
  return net;
}

TEST(NameRules, HiddenLinesLeaveEdgesAndStationsOnlyTheyUsed) {
  auto net = small_network();
  MetroRules r;
  r.hide_lines = {"*bau"};
  r.strip_prefixes = {"U "};
  r.strip_suffixes = {" (Berlin)"};
  auto report = apply_metro_rules(net, r);
  ASSERT_EQ(net.lines.size(), 1u);
  EXPECT_EQ(net.lines[0].label, "U1");
  EXPECT_EQ(report.hidden_lines, std::vector<std::string>{"U1bau"});
  EXPECT_EQ(report.removed_edges, 2u);  // c-j and j-d
  EXPECT_EQ(report.removed_stations, 1u);  // d
  EXPECT_EQ(report.removed_junctions, 1u);  // j
  ASSERT_EQ(net.edges.size(), 2u);
  std::vector<std::string> names;
  for (const auto& n : net.nodes) names.push_back(n.name);
  EXPECT_EQ(names, (std::vector<std::string>{"a", "b", "c", "e"}));  // e had no edge in the data: it stays
  for (const auto& e : net.edges) {
    EXPECT_EQ(e.lines, std::vector<std::uint32_t>{0});
    EXPECT_LT(e.from, net.nodes.size());
    EXPECT_LT(e.to, net.nodes.size());
  }
  EXPECT_EQ(net.nodes[net.edges[1].from].name, "b");
  EXPECT_EQ(net.nodes[net.edges[1].to].name, "c");
  EXPECT_EQ(report.names_changed, 4u);
}

TEST(NameRules, HidesByIdAndOverridesLabelsAndColours) {
  auto net = small_network();
  MetroRules r;
  r.hide_lines = {"l2"};
  r.lines = {{"l1", {"Line 1", "#00782A"}}};
  auto report = apply_metro_rules(net, r);
  ASSERT_EQ(net.lines.size(), 1u);
  EXPECT_EQ(net.lines[0].label, "Line 1");
  EXPECT_EQ(net.lines[0].color, "00782A");
  EXPECT_EQ(report.lines_overridden, 1u);
  EXPECT_EQ(net.nodes[0].name, "U a (Berlin)");  // no name rules: names stay
}

TEST(NameRules, RulesTheNetworkCannotTakeThrow) {
  auto net = small_network();
  MetroRules unknown;
  unknown.lines = {{"l9", {"X", ""}}};
  EXPECT_THROW(apply_metro_rules(net, unknown), std::invalid_argument);
  MetroRules all;
  all.hide_lines = {"U*"};
  EXPECT_THROW(apply_metro_rules(net, all), std::invalid_argument);
  EXPECT_EQ(net.lines.size(), 2u);  // unchanged when refused
}

TEST(NameRules, ErrorsNameTheField) {
  MetroRules r;
  EXPECT_EQ(rules_error(r), "");
  EXPECT_TRUE(r.empty());
  r.strip_suffixes = {" (Berlin)", "*"};
  EXPECT_EQ(rules_error(r).rfind("strip_suffixes[1]: ", 0), 0u) << rules_error(r);
  r = {};
  r.drop_brackets = {"(]"};
  EXPECT_EQ(rules_error(r).rfind("drop_brackets[0]: ", 0), 0u) << rules_error(r);
  r = {};
  r.particles = {"de la"};
  EXPECT_EQ(rules_error(r).rfind("particles[0]: ", 0), 0u) << rules_error(r);
  r = {};
  r.rename = {{"A", "B"}, {"B", "C"}};
  EXPECT_EQ(rules_error(r).rfind("rename['A']: ", 0), 0u) << rules_error(r);
  r = {};
  r.lines = {{"4", {"", "00A16"}}};
  EXPECT_EQ(rules_error(r).rfind("lines['4'].color: ", 0), 0u) << rules_error(r);
  r = {};
  r.lines = {{"4", {"", ""}}};
  EXPECT_EQ(rules_error(r).rfind("lines['4']: ", 0), 0u) << rules_error(r);
  r = {};
  r.min_colour_difference = -1;
  EXPECT_EQ(rules_error(r).rfind("min_colour_difference: ", 0), 0u) << rules_error(r);
  r = {};
  r.hide_lines.assign(kMaxRulePatterns + 1, "x");
  EXPECT_EQ(rules_error(r).rfind("hide_lines: ", 0), 0u) << rules_error(r);
}

}  // namespace
}  // namespace tourmap::load
