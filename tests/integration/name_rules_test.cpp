// Name and line rules over HTTP: a manifest (and a station-csvs upload) with rules is imported
// into a running server, which then serves clean names, no hidden line and styles for lines of
// close colours in every line list.

#include "live_server.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

namespace tourmap::test {
namespace {

// Berlin and Lisbon with the sample manifest's rules; London without its colour overrides, so
// its District and DLR greens (as in the data) are too close and the DLR must be told apart.
std::string rules_manifest() {
  return R"j({"cities": [
    {"id": "berlin", "name": "Berlin", "metro": {"format": "loom", "files": ["metro/loom_berlin.json"],
      "rules": {"drop_brackets": ["[]"], "strip_prefixes": ["Berlin, ", "S+U ", "U "],
                "strip_suffixes": [" (Berlin)", " (Bln)", " Bhf", " U#"],
                "rename": {"Berlin Hauptbahnhof": "Hauptbahnhof"}, "hide_lines": ["*bau"]}}},
    {"id": "lisbon", "name": "Lisbon", "metro": {"format": "line-csv", "files": ["metro/lisbon_metro_stations_metrodroid.csv"],
      "rules": {"title_case": true, "particles": ["de", "do", "da", "dos", "das", "e"],
                "rename": {"Cais do Sodre": "Cais do Sodré"}}}},
    {"id": "london", "name": "London", "metro": {"format": "station-csvs",
      "files": ["metro/london.stations.csv", "metro/london.lines.csv", "metro/london.connections.csv"]}}]})j";
}

const char* kU5 = "0x18d2e50";
const char* kU55 = "0x18d2f50";
const char* kU55bau = "0x18d2f501";

CommandResult import_manifest(const LiveServer& live, const std::string& name, const std::string& text) {
  auto file = live.dir.write(name, text);
  return run_command({kTourmapBin, "import", "manifest", file, "--data-dir", data_dir(), "--db", live.db()});
}

std::map<std::string, nlohmann::json> lines_by_id(const nlohmann::json& lines) {
  std::map<std::string, nlohmann::json> out;
  for (const auto& l : lines) out[l["id"].get<std::string>()] = l;
  return out;
}

bool plain(const nlohmann::json& line) {
  return line.at("style").at("casing") == false && line.at("style").at("dash").empty();
}

std::set<std::string> station_names(const nlohmann::json& metro) {
  std::set<std::string> names;
  for (const auto& f : metro["features"])
    if (f["properties"]["kind"] == "station") names.insert(f["properties"]["name"].get<std::string>());
  return names;
}

TEST(NameRulesApi, ManifestRulesServeCleanNamesNoHiddenLineAndStyles) {
  LiveServer live;  // Lisbon already imported, without rules
  EXPECT_TRUE(station_names(live.get_json("/api/v1/cities/lisbon/metro")).count("MARQU\xC3\x8AS DE POMBAL"));
  auto r = import_manifest(live, "rules.json", rules_manifest());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("U55 casing (close to U5)"), std::string::npos) << r.output;

  // City detail: the construction line is gone, U55 (U5's brown) has a casing, the rest plain.
  auto berlin = live.get_json("/api/v1/cities/berlin");
  auto lines = lines_by_id(berlin["lines"]);
  EXPECT_EQ(lines.size(), 10u);
  EXPECT_FALSE(lines.count(kU55bau));
  EXPECT_EQ(lines.at(kU55)["style"]["casing"], true);
  EXPECT_TRUE(lines.at(kU55)["style"]["dash"].empty());
  for (const auto& [id, line] : lines) {
    if (id != kU55) {
      EXPECT_TRUE(plain(line)) << line;
    }
  }

  // Metro GeoJSON: clean names, no edge of the hidden line, the line table with styles.
  auto metro = live.get_json("/api/v1/cities/berlin/metro");
  auto names = station_names(metro);
  EXPECT_EQ(names.size(), 172u);
  for (const char* clean : {"Alt-Tegel", "Wittenau", "Potsdamer Platz", "Stadtmitte", "Hauptbahnhof", "Friedrichstr.",
                            "Freie Universit\xC3\xA4t (Thielplatz)"})
    EXPECT_TRUE(names.count(clean)) << clean;
  for (const auto& name : names) {
    EXPECT_EQ(name.find("(Berlin)"), std::string::npos) << name;
    EXPECT_EQ(name.find('['), std::string::npos) << name;
    EXPECT_NE(name.rfind("U ", 0), 0u) << name;
    EXPECT_NE(name.rfind("S+U ", 0), 0u) << name;
  }
  std::size_t edges = 0;
  for (const auto& f : metro["features"]) {
    if (f["properties"]["kind"] != "edge") continue;
    ++edges;
    for (const auto& id : f["properties"]["lines"]) EXPECT_NE(id, kU55bau);
  }
  EXPECT_EQ(edges, 189u);  // the data's 190 less the one only U55bau ran on
  EXPECT_EQ(lines_by_id(metro["lines"]).at(kU55)["style"]["casing"], true);
  EXPECT_TRUE(plain(lines_by_id(metro["lines"]).at(kU5)));

  // The layout draws the same network with the same line table.
  auto layout = live.get_json("/api/v1/cities/berlin/layout?solver=fast");
  EXPECT_EQ(layout["edges"]["features"].size(), 189u);
  for (const auto& f : layout["edges"]["features"])
    for (const auto& id : f["properties"]["lines"]) EXPECT_NE(id, kU55bau);
  auto layout_lines = lines_by_id(layout["lines"]);
  EXPECT_FALSE(layout_lines.count(kU55bau));
  EXPECT_EQ(layout_lines.at(kU55)["style"]["casing"], true);
  for (const auto& f : layout["stations"]["features"])
    EXPECT_EQ(f["properties"]["name"].get<std::string>().find("(Berlin)"), std::string::npos);

  // Lisbon: title case with lower-case particles and accents, and the rename.
  auto lisbon = station_names(live.get_json("/api/v1/cities/lisbon/metro"));
  for (const char* clean : {"Marqu\xC3\xAAs de Pombal", "Pra\xC3\xA7" "a de Espanha", "Alto dos Moinhos",
                            "S\xC3\xA3o Sebasti\xC3\xA3o", "Col\xC3\xA9gio Militar-Luz", "Cais do Sodr\xC3\xA9", "Arroios"})
    EXPECT_TRUE(lisbon.count(clean)) << clean;
  EXPECT_FALSE(lisbon.count("MARQU\xC3\x8AS DE POMBAL"));

  // London without overrides: the DLR is the District's green, so it gets the casing.
  for (const auto& [id, line] : lines_by_id(live.get_json("/api/v1/cities/london")["lines"]))
    EXPECT_EQ(line["style"]["casing"], line["label"] == "Docklands Light Railway") << line;

  // The same manifest again changes nothing; a changed rule imports that city again.
  const auto version = berlin["version"];
  r = import_manifest(live, "rules.json", rules_manifest());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("berlin               unchanged"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("lisbon               unchanged"), std::string::npos) << r.output;
  EXPECT_EQ(live.get_json("/api/v1/cities/berlin")["version"], version);
  auto changed = rules_manifest();
  changed.replace(changed.find("\"hide_lines\": [\"*bau\"]"), std::string("\"hide_lines\": [\"*bau\"]").size(),
                  "\"hide_lines\": []");
  r = import_manifest(live, "changed.json", changed);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("berlin               unchanged"), std::string::npos) << r.output;
  EXPECT_NE(live.get_json("/api/v1/cities/berlin")["version"], version);
  EXPECT_TRUE(lines_by_id(live.get_json("/api/v1/cities/berlin")["lines"]).count(kU55bau));
}

TEST(NameRulesApi, BadManifestRulesAreNamedAndChangeNothing) {
  LiveServer live;
  const auto before = live.get("/api/v1/cities/lisbon/metro").body;
  auto bad = rules_manifest();
  bad.replace(bad.find("\"title_case\": true"), std::string("\"title_case\": true").size(), "\"title_case\": 1");
  auto r = import_manifest(live, "bad.json", bad);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("cities[lisbon].metro.rules.title_case: expected true or false"), std::string::npos)
      << r.output;
  EXPECT_EQ(live.get("/api/v1/cities/lisbon/metro").body, before);
  EXPECT_EQ(live.get("/api/v1/cities/berlin").status, 404);  // the manifest is refused before any import
}

TEST(NameRulesApi, StationCsvUploadTakesRules) {
  LiveServer live;
  auto key = create_key(live);
  nlohmann::json body = {{"stations", file_bytes(data_file("metro/london.stations.csv"))},
                         {"lines", file_bytes(data_file("metro/london.lines.csv"))},
                         {"connections", file_bytes(data_file("metro/london.connections.csv"))}};
  auto put = [&](const nlohmann::json& b) {
    return http_request(live.port(), "PUT", "/api/v1/cities/london/metro?format=station-csvs&name=London",
                        {{"X-API-Key", key}, {"Content-Type", "application/json"}}, b.dump());
  };

  // A malformed rule: 400 naming it, nothing imported.
  body["rules"] = {{"lines", {{"4", {{"color", "green"}}}}}};
  auto r = put(body);
  EXPECT_EQ(r.status, 400) << r.body;
  EXPECT_EQ(error_of(r)["field"], "rules");
  EXPECT_NE(error_of(r)["message"].get<std::string>().find("rules.lines['4'].color"), std::string::npos) << r.body;
  EXPECT_EQ(live.get("/api/v1/cities/london").status, 404);
  // A rule for a line the network does not have: 400 too.
  body["rules"] = {{"lines", {{"99", {{"color", "00782A"}}}}}};
  r = put(body);
  EXPECT_EQ(r.status, 400) << r.body;
  EXPECT_NE(error_of(r)["message"].get<std::string>().find("no line with id '99'"), std::string::npos) << r.body;
  EXPECT_EQ(live.get("/api/v1/cities/london").status, 404);

  body["rules"] = {{"strip_suffixes", {" (B)", " (C)"}},
                   {"lines", {{"4", {{"color", "00782A"}}}, {"13", {{"color", "00A4A7"}}}, {"12", {{"color", "95CDBA"}}}}}};
  r = put(body);
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(nlohmann::json::parse(r.body)["skipped"], false);
  auto lines = lines_by_id(live.get_json("/api/v1/cities/london")["lines"]);
  EXPECT_EQ(lines.at("4")["color"], "00782A");
  EXPECT_EQ(lines.at("13")["color"], "00A4A7");
  for (const auto& [id, line] : lines) EXPECT_TRUE(plain(line)) << line;  // TfL's colours are far enough apart
  auto names = station_names(live.get_json("/api/v1/cities/london/metro"));
  EXPECT_TRUE(names.count("Edgware Road"));
  EXPECT_FALSE(names.count("Edgware Road (B)"));
  // The same body again is a no-op.
  r = put(body);
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(nlohmann::json::parse(r.body)["skipped"], true);
}

}  // namespace
}  // namespace tourmap::test
