#include "store/metro_rules.hpp"

#include "load/file.hpp"
#include "load/utf8.hpp"
#include "metro/line_styles.hpp"
#include "store/importer.hpp"
#include "store/manifest.hpp"
#include "store/migrate.hpp"
#include "store/repo.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace tourmap::store {
namespace {

using test::data_file;

std::string parse_error(const std::string& json) {
  try {
    parse_metro_rules(nlohmann::json::parse(json), "rules");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(MetroRulesJson, ParsesEveryField) {
  auto r = parse_metro_rules(nlohmann::json::parse(R"j({
      "strip_prefixes": ["S+U ", "U "], "strip_suffixes": [" (Berlin)", " U#"], "drop_brackets": ["[]"],
      "title_case": true, "particles": ["de", "do"], "rename": {"CAIS DO SODRE": "Cais do Sodré"},
      "hide_lines": ["*bau"], "lines": {"4": {"color": "#00782A"}, "13": {"label": "DLR", "color": "00A4A7"}},
      "min_colour_difference": 12.5})j"),
                             "rules");
  EXPECT_EQ(r.strip_prefixes, (std::vector<std::string>{"S+U ", "U "}));
  EXPECT_EQ(r.strip_suffixes, (std::vector<std::string>{" (Berlin)", " U#"}));
  EXPECT_EQ(r.drop_brackets, std::vector<std::string>{"[]"});
  EXPECT_TRUE(r.title_case);
  EXPECT_EQ(r.particles, (std::vector<std::string>{"de", "do"}));
  EXPECT_EQ(r.rename.at("CAIS DO SODRE"), "Cais do Sodr\xC3\xA9");
  EXPECT_EQ(r.hide_lines, std::vector<std::string>{"*bau"});
  EXPECT_EQ(r.lines.at("4").color, "#00782A");
  EXPECT_EQ(r.lines.at("13").label, "DLR");
  EXPECT_EQ(r.min_colour_difference, 12.5);
  // The canonical JSON reads back as the same rules, and equal rules give equal text.
  auto canonical = metro_rules_json(r);
  EXPECT_EQ(parse_metro_rules(canonical, "rules"), r);
  EXPECT_EQ(metro_rules_json(parse_metro_rules(canonical, "rules")).dump(), canonical.dump());
  EXPECT_EQ(metro_rules_json({}).dump(), "{}");
}

TEST(MetroRulesJson, ErrorsNameTheField) {
  EXPECT_EQ(parse_error("[]"), "rules: expected an object");
  EXPECT_EQ(parse_error(R"j({"strip_prefix": ["U "]})j").rfind("rules: unknown field 'strip_prefix' (expected strip_prefixes", 0),
            0u);
  EXPECT_EQ(parse_error(R"j({"strip_prefixes": "U "})j"), "rules.strip_prefixes: expected an array of strings");
  EXPECT_EQ(parse_error(R"j({"strip_prefixes": ["U ", 3]})j"), "rules.strip_prefixes[1]: expected a string");
  EXPECT_EQ(parse_error(R"j({"title_case": "yes"})j"), "rules.title_case: expected true or false");
  EXPECT_EQ(parse_error(R"j({"rename": {"A": ""}})j"), "rules.rename['A']: empty");
  EXPECT_EQ(parse_error(R"j({"lines": {"4": {"colour": "00782A"}}})j"),
            "rules.lines['4']: unknown field 'colour' (expected label, color)");
  EXPECT_EQ(parse_error(R"j({"lines": {"4": "00782A"}})j").rfind("rules.lines['4']: expected an object", 0), 0u);
  EXPECT_EQ(parse_error(R"j({"min_colour_difference": "10"})j"), "rules.min_colour_difference: expected a number");
  // Content checks of the core (load::rules_error), under the same path.
  EXPECT_EQ(parse_error(R"j({"hide_lines": ["*"]})j").rfind("rules.hide_lines[0]: '*' matches the empty text", 0), 0u);
  EXPECT_EQ(parse_error(R"j({"lines": {"4": {"color": "green"}}})j").rfind("rules.lines['4'].color: 'green'", 0), 0u);
  EXPECT_EQ(parse_error(R"j({"drop_brackets": ["«»"]})j").rfind("rules.drop_brackets[0]: ", 0), 0u);
}

TEST(MetroRulesJson, ManifestErrorsNameTheCity) {
  try {
    parse_manifest(R"j({"cities": [{"id": "berlin", "name": "Berlin",
        "metro": {"format": "loom", "files": ["metro/loom_berlin.json"], "rules": {"strip_suffixes": ["x\\"]}}}]})j",
                   "/data");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("cities[berlin].metro.rules.strip_suffixes[0]: ", 0), 0u) << e.what();
  }
}

class MetroRulesImport : public ::testing::Test {
 protected:
  MetroRulesImport() : db(dir.file("t.db")) { migrate(db); }

  MetroImport berlin(const std::string& rules_json) {
    MetroImport req{{"berlin", "Berlin", ""}, MetroFormat::loom, {data_file("metro/loom_berlin.json")}, false};
    req.rules = parse_metro_rules(nlohmann::json::parse(rules_json), "rules");
    return req;
  }

  const model::MetroNode* station(const model::City& city, const std::string& name) {
    for (const auto& n : city.metro.nodes)
      if (n.name == name) return &n;
    return nullptr;
  }

  test::TempDir dir;
  Db db;
};

TEST_F(MetroRulesImport, StoresCleanNamesAndStylesAndReimportsOnlyOnChange) {
  const std::string rules = R"j({"drop_brackets": ["[]"], "strip_prefixes": ["Berlin, ", "S+U ", "U "],
      "strip_suffixes": [" (Berlin)", " (Bln)", " Bhf", " U#"], "hide_lines": ["*bau"]})j";
  auto first = import_metro(db, berlin(rules));
  EXPECT_FALSE(first.skipped);
  EXPECT_NE(first.summary.find("1 line(s) hidden (U55bau: 1 edges"), std::string::npos) << first.summary;
  EXPECT_NE(first.summary.find("styles: U55 casing (close to U5)"), std::string::npos) << first.summary;
  auto city = load_city(db, "berlin");
  ASSERT_TRUE(city);
  EXPECT_TRUE(station(*city, "Alt-Tegel"));
  EXPECT_TRUE(station(*city, "Wittenau"));
  EXPECT_TRUE(station(*city, "Stadtmitte"));
  EXPECT_FALSE(station(*city, "U Alt-Tegel (Berlin)"));
  EXPECT_EQ(city->metro.lines.size(), 10u);
  EXPECT_EQ(city->metro.edges.size(), 189u);  // 190 in the data, one only U55bau ran on
  for (const auto& l : city->metro.lines) {
    EXPECT_NE(l.label, "U55bau");
    EXPECT_EQ(l.style.casing, l.label == "U55") << l.label;  // read back from the store
  }

  // The same files and rules: nothing to do. A changed rule imports again.
  auto again = import_metro(db, berlin(rules));
  EXPECT_TRUE(again.skipped);
  EXPECT_EQ(again.version, first.version);
  auto changed = import_metro(db, berlin(R"j({"hide_lines": ["*bau"]})j"));
  EXPECT_FALSE(changed.skipped);
  EXPECT_GT(changed.version, first.version);
  EXPECT_TRUE(station(*load_city(db, "berlin"), "U Alt-Tegel (Berlin)"));
  // Without rules the city imports again too, and the construction line is back.
  auto none = import_metro(db, berlin("{}"));
  EXPECT_FALSE(none.skipped);
  EXPECT_EQ(load_city(db, "berlin")->metro.lines.size(), 11u);
  EXPECT_TRUE(import_metro(db, berlin("{}")).skipped);
}

TEST_F(MetroRulesImport, RulesTheNetworkCannotTakeChangeNothing) {
  import_metro(db, berlin("{}"));
  auto before = load_city(db, "berlin")->info.version;
  EXPECT_THROW(import_metro(db, berlin(R"j({"lines": {"no-such-line": {"label": "X"}}})j")), std::invalid_argument);
  EXPECT_THROW(import_metro(db, berlin(R"j({"hide_lines": ["U*"]})j")), std::invalid_argument);
  MetroImport invalid = berlin("{}");
  invalid.rules.strip_prefixes = {"*"};  // built in code, not parsed: checked all the same
  EXPECT_THROW(import_metro(db, invalid), std::invalid_argument);
  EXPECT_EQ(load_city(db, "berlin")->info.version, before);
}

// The sample import (scripts/sample-data.json) serves no name with the noise its rules remove.
TEST_F(MetroRulesImport, SampleManifestServesCleanNames) {
  auto manifest = parse_manifest(load::read_file(std::string(TOURMAP_SOURCE_DIR) + "/scripts/sample-data.json"),
                                 test::data_dir());
  manifest.pois.clear();
  manifest.roads.clear();
  run_manifest(db, manifest, false, nullptr);
  auto names = [&](const std::string& id) {
    std::vector<std::string> out;
    const auto city = load_city(db, id);
    for (const auto& n : city->metro.nodes)
      if (n.is_station()) out.push_back(n.name);
    return out;
  };
  for (const auto& name : names("berlin")) {
    for (const char* noise : {"(Berlin)", "(Bln)", "[", "Bhf", "Berlin,"}) EXPECT_EQ(name.find(noise), std::string::npos) << name;
    EXPECT_NE(name.rfind("U ", 0), 0u) << name;
    EXPECT_NE(name.rfind("S+U ", 0), 0u) << name;
  }
  for (const auto& name : names("lisbon")) EXPECT_FALSE(load::is_all_caps(name)) << name;
  auto lisbon = names("lisbon");
  for (const char* expected : {"Marqu\xC3\xAAs de Pombal", "Cais do Sodr\xC3\xA9", "Senhor Roubado", "Alto dos Moinhos",
                               "S\xC3\xA3o Sebasti\xC3\xA3o", "Arroios"})
    EXPECT_NE(std::find(lisbon.begin(), lisbon.end(), expected), lisbon.end()) << expected;
  for (const auto& name : names("chicago")) EXPECT_EQ(name.find('('), std::string::npos) << name;
  for (const auto& name : names("stuttgart")) EXPECT_EQ(name.find(", "), std::string::npos) << name;
  for (const auto& name : names("london")) {
    EXPECT_EQ(name.find(" (B)"), std::string::npos) << name;
    EXPECT_EQ(name.find(" (C)"), std::string::npos) << name;
    EXPECT_EQ(name.find(" (H)"), std::string::npos) << name;
  }
  const auto berlin = load_city(db, "berlin");
  for (const auto& l : berlin->metro.lines) EXPECT_NE(l.label, "U55bau");
  const auto chicago = load_city(db, "chicago");
  for (const auto& l : chicago->metro.lines) EXPECT_NE(l.label.rfind("0x", 0), 0u) << l.label;
  // London's District, DLR and Waterloo & City: told apart by colour now.
  auto london = load_city(db, "london")->metro.lines;
  for (const auto& a : london) {
    for (const auto& b : london) {
      if (&a == &b || a.style != b.style) continue;
      EXPECT_GE(metro::delta_e2000(*metro::lab_from_hex(a.color), *metro::lab_from_hex(b.color)),
                metro::kMinColourDifference)
          << a.label << " / " << b.label;
    }
  }
  // The same manifest again changes nothing.
  for (const auto& r : run_manifest(db, manifest, false, nullptr)) EXPECT_TRUE(r.skipped) << r.target;
}

}  // namespace
}  // namespace tourmap::store
