#include "load/load_error.hpp"
#include "load/metro_load.hpp"
#include "test_data.hpp"

#include "load/poi_load.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace tourmap::load {
namespace {

using test::data_file;

const model::MetroNode* find_station(const model::MetroNetwork& net, const std::string& name) {
  for (const auto& n : net.nodes)
    if (n.name == name) return &n;
  return nullptr;
}

TEST(MetroLoom, LoadsViennaUBahn) {
  auto net = load_metro_loom(data_file("metro/loom_wien.json"));
  EXPECT_EQ(net.nodes.size(), 99u);
  EXPECT_EQ(net.station_count(), 98u);  // one junction without station_id
  EXPECT_EQ(net.edges.size(), 105u);
  ASSERT_EQ(net.lines.size(), 5u);
  std::vector<std::string> labels;
  for (const auto& l : net.lines) labels.push_back(l.label);
  std::sort(labels.begin(), labels.end());
  EXPECT_EQ(labels, (std::vector<std::string>{"U1", "U2", "U3", "U4", "U6"}));
  for (const auto& e : net.edges) {
    ASSERT_GE(e.geometry.size(), 2u);
    // Geometry runs from `from` to `to` (reversed on load where LOOM stores it the other way).
    auto dist = [](geo::LonLat a, geo::LonLat b) { return std::hypot(a.lon - b.lon, a.lat - b.lat); };
    EXPECT_LE(dist(e.geometry.front(), net.nodes[e.from].pos), dist(e.geometry.front(), net.nodes[e.to].pos));
  }
  EXPECT_NE(find_station(net, "Stephansplatz"), nullptr);
}

TEST(MetroLoom, LoadsEveryLoomFile) {
  struct Case { const char* file; std::size_t stations, edges, lines; };
  for (auto c : {Case{"metro/loom_berlin.json", 172, 190, 11}, Case{"metro/loom_stuttgart.json", 192, 228, 15},
                 Case{"metro/loom_sydney.json", 175, 200, 9}, Case{"metro/loom_chicago.json", 143, 154, 8},
                 Case{"metro/loom_freiburg.json", 74, 79, 5}}) {
    auto net = load_metro_loom(data_file(c.file));
    EXPECT_EQ(net.station_count(), c.stations) << c.file;
    EXPECT_EQ(net.edges.size(), c.edges) << c.file;
    EXPECT_EQ(net.lines.size(), c.lines) << c.file;
  }
}

TEST(MetroLoom, EdgeToUnknownNodeNamesTheFeature) {
  const char* doc = R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"id":"a","station_id":"A","station_label":"A"},"geometry":{"type":"Point","coordinates":[1,2]}},
    {"type":"Feature","properties":{"from":"a","to":"zz","lines":[]},"geometry":{"type":"LineString","coordinates":[[1,2],[1,3]]}}]})";
  try {
    parse_metro_loom(doc, "bad.json");
    FAIL();
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where(), "bad.json feature 1");
    EXPECT_NE(std::string(e.what()).find("unknown station or node 'zz'"), std::string::npos);
  }
}

TEST(MetroLoom, RejectsDuplicateIdsBadCoordinatesAndNonCollections) {
  EXPECT_THROW(parse_metro_loom(R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"id":"a","station_id":"A"},"geometry":{"type":"Point","coordinates":[1,2]}},
    {"type":"Feature","properties":{"id":"a","station_id":"B"},"geometry":{"type":"Point","coordinates":[1,3]}}]})",
                                "d.json"),
               LoadError);
  EXPECT_THROW(parse_metro_loom(R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"id":"a","station_id":"A"},"geometry":{"type":"Point","coordinates":[200,2]}}]})",
                                "c.json"),
               LoadError);
  EXPECT_THROW(parse_metro_loom(R"({"type":"Feature"})", "f.json"), LoadError);
  EXPECT_THROW(parse_metro_loom(R"({"type":"FeatureCollection","features":[)", "t.json"), LoadError);
  EXPECT_THROW(parse_metro_loom(R"({"type":"FeatureCollection","features":[]})", "e.json"), LoadError);  // no stations
}

// A "type" that is not a string was a json type_error (500 over HTTP), not a LoadError.
TEST(MetroLoom, NonStringTypesAreLoadErrors) {
  EXPECT_THROW(parse_metro_loom(R"({"type": 1})", "n.json"), LoadError);
  EXPECT_THROW(parse_metro_loom(R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"id":"a"},"geometry":{"type":["Point"],"coordinates":[1,2]}}]})",
                                "g.json"),
               LoadError);
  EXPECT_THROW(load::parse_pois_geojson(R"({"type": {}})", "p.json"), LoadError);
  EXPECT_THROW(load::parse_pois_geojson(R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"name":"a"},"geometry":{"type":7,"coordinates":[1,2]}}]})",
                                        "q.json"),
               LoadError);
}

// The fuzzers' number overflow (see Params.JsonNumberTooLargeForADoubleIs400) in the loaders'
// load::parse_json: a LOOM or POI file holding 1e309 threw nlohmann's out_of_range, not the
// LoadError the loaders promise.
TEST(MetroLoom, NumberTooLargeForADoubleIsALoadError) {
  EXPECT_THROW(parse_metro_loom(R"({"type":"FeatureCollection","features":[{"type":"Feature",
    "properties":{"id":"a"},"geometry":{"type":"Point","coordinates":[16.3,48.11e308]}}]})",
                                "big.json"),
               LoadError);
  EXPECT_THROW(load::parse_pois_geojson(R"({"type":"FeatureCollection","features":[1e309]})", "p.json"), LoadError);
  EXPECT_THROW(load::parse_pois_js_array("var x = [{\"name\": \"a\", \"lon\": -1e999, \"lat\": 0}];", "p.js"), LoadError);
}

TEST(MetroStationCsvs, LoadsLondonAndMergesParallelLines) {
  auto net = load_metro_station_csvs(data_file("metro/london.stations.csv"), data_file("metro/london.lines.csv"),
                                     data_file("metro/london.connections.csv"));
  EXPECT_EQ(net.station_count(), 302u);
  EXPECT_EQ(net.lines.size(), 13u);
  // 406 connections, several lines sharing track between the same two stations.
  EXPECT_LT(net.edges.size(), 406u);
  std::size_t line_refs = 0;
  for (const auto& e : net.edges) line_refs += e.lines.size();
  EXPECT_EQ(line_refs, 406u);
  const auto* acton = find_station(net, "Acton Town");
  ASSERT_NE(acton, nullptr);
  EXPECT_NEAR(acton->pos.lat, 51.5028, 1e-9);
}

TEST(MetroStationCsvs, UnknownStationNamesTheLine) {
  LondonCsvText files{"id,latitude,longitude,name\n1,51.5,-0.1,A\n2,51.6,-0.1,B\n", "line,name,colour\n1,L,ff0000\n",
                      "station1,station2,line\n1,2,1\n1,9,1\n", "s.csv", "l.csv", "c.csv"};
  try {
    parse_metro_station_csvs(files);
    FAIL();
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where(), "c.csv line 3");
  }
}

TEST(MetroStationCsvs, MissingColumnIsAnError) {
  LondonCsvText files{"id,latitude,name\n1,51.5,A\n", "line,name\n1,L\n", "station1,station2,line\n", "s.csv", "l.csv",
                      "c.csv"};
  try {
    parse_metro_station_csvs(files);
    FAIL();
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("missing column 'longitude'"), std::string::npos);
  }
}

TEST(MetroLineCsv, LoadsLisbonWithSharedTransferStations) {
  auto net = load_metro_line_csv(data_file("metro/lisbon_metro_stations_metrodroid.csv"));
  EXPECT_EQ(net.station_count(), 50u);  // 55 rows, 5 transfer stations listed twice
  EXPECT_EQ(net.lines.size(), 4u);
  EXPECT_EQ(net.edges.size(), 51u);  // 16 + 12 + 12 + 11 consecutive pairs
  for (const auto& l : net.lines) EXPECT_FALSE(l.color.empty()) << l.label;  // named after colours
  const auto* marques = find_station(net, "MARQU\xC3\x8AS DE POMBAL");
  ASSERT_NE(marques, nullptr);
  std::size_t degree = 0;
  auto index = static_cast<std::uint32_t>(marques - net.nodes.data());
  for (const auto& e : net.edges) degree += (e.from == index || e.to == index) ? 1 : 0;
  EXPECT_EQ(degree, 4u);  // on Azul and Amarela, both passing through
}

TEST(MetroLineCsv, DuplicatePositionAndBadNumbers) {
  EXPECT_THROW(parse_metro_line_csv("line_id,seq_on_line,name,lat,lon\nA,1,X,38.7,-9.1\nA,1,Y,38.8,-9.1\n", "d.csv"),
               LoadError);
  try {
    parse_metro_line_csv("line_id,seq_on_line,name,lat,lon\nA,1,X,north,-9.1\n", "n.csv");
    FAIL();
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where(), "n.csv line 2");
  }
}

}  // namespace
}  // namespace tourmap::load
