// Imports while the server runs: new data is served without a restart; a failed import changes
// nothing and the server keeps serving.

#include "live_server.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <thread>

namespace tourmap::test {
namespace {

std::vector<std::string> city_ids(const LiveServer& live) {
  std::vector<std::string> ids;
  auto cities = live.get_json("/api/v1/cities");
  for (const auto& c : cities["cities"]) ids.push_back(c["id"]);
  return ids;
}

TEST(ImportLive, NewCityAndRoadsAreServedWithoutRestart) {
  LiveServer live;
  EXPECT_EQ(city_ids(live).size(), 2u);
  auto r = run_command({kTourmapBin, "import", "metro", data_file("metro/loom_freiburg.json"), "--city", "freiburg",
                        "--name", "Freiburg", "--db", live.db()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("74 stations"), std::string::npos) << r.output;
  auto ids = city_ids(live);
  EXPECT_NE(std::find(ids.begin(), ids.end(), "freiburg"), ids.end());
  auto metro = live.get_json("/api/v1/cities/freiburg/metro");
  EXPECT_GT(metro["features"].size(), 74u);
  // With its POIs, the new city has a layout and clusters: nothing else is needed.
  auto sights = live.dir.write("freiburg.csv",
                               "name,lon,lat\nMuenster,7.8529,47.9956\nSchwabentor,7.8560,47.9918\nAugustinermuseum,7.8527,47.9930\n");
  r = run_command({kTourmapBin, "import", "pois", sights, "--city", "freiburg", "--db", live.db()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto layout = live.get_json("/api/v1/cities/freiburg/layout?solver=fast");
  EXPECT_EQ(layout["stations"]["features"].size(), 74u);
  EXPECT_EQ(layout["pois"]["features"].size(), 3u);
  EXPECT_EQ(layout["quality"]["octilinear_share"], 1.0);
  EXPECT_EQ(layout["quality"]["added_crossings"], 0);
  auto clusters = live.get_json("/api/v1/cities/freiburg/clusters?m=2");
  EXPECT_EQ(clusters["clusters"].size(), 2u);
  EXPECT_EQ(clusters["active"], 3);  // refined down to single sights
  EXPECT_EQ(live.get_json("/api/v1/cities/freiburg/visual-worth?width=8&height=8")["values"].size(), 64u);

  // Re-import changes POIs of a city already held in memory: the next read sees them.
  EXPECT_EQ(live.get_json("/api/v1/cities/vienna/pois")["matched"], 63);
  auto museums = live.dir.write("museums.csv", "name,lon,lat\nAlbertina,16.3681,48.2046\nBelvedere,16.3809,48.1915\n");
  r = run_command({kTourmapBin, "import", "pois", museums, "--city", "vienna", "--db", live.db()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(live.get_json("/api/v1/cities/vienna/pois")["matched"], 2);

  r = run_command({kTourmapBin, "import", "roads", data_file("roads/berlin-siegessaeule.osm.gz"), "--id", "tiergarten",
                   "--name", "Tiergarten", "--db", live.db()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(live.get_json("/api/v1/roads")["roads"].size(), 3u);
  EXPECT_GT(live.get_json("/api/v1/roads/tiergarten")["edges"].get<int>(), 1000);
}

TEST(ImportLive, FailedImportsChangeNothing) {
  LiveServer live;
  auto cities_before = live.get("/api/v1/cities").body;
  auto roads_before = live.get("/api/v1/roads").body;
  auto lisbon_before = live.get("/api/v1/cities/lisbon/metro").body;

  // A truncated OSM extract, replacing an existing network.
  std::ifstream in(data_file("roads/monaco.osm.gz"), std::ios::binary);
  std::stringstream buf;
  buf << in.rdbuf();
  auto cut = live.dir.write("cut.osm.gz", buf.str().substr(0, buf.str().size() / 3));
  auto r = run_command({kTourmapBin, "import", "roads", cut, "--id", "monaco", "--name", "Monaco", "--db", live.db()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("nothing was changed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cut.osm.gz"), std::string::npos) << r.output;

  // A CSV with a missing column, replacing Lisbon.
  auto csv = live.dir.write("lisbon.csv", "line_id,seq_on_line,name,lat\nA,1,X,38.7\n");
  r = run_command({kTourmapBin, "import", "metro", csv, "--format", "line-csv", "--city", "lisbon", "--name", "Lisbon",
                   "--db", live.db(), "--force"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("missing column 'lon'"), std::string::npos) << r.output;

  // A LOOM file with an edge to an unknown station: the error names the feature.
  auto loom = live.dir.write("bad.json", R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"id":"a","station_id":"A"},"geometry":{"type":"Point","coordinates":[1,2]}},
    {"type":"Feature","properties":{"from":"a","to":"b"},"geometry":{"type":"LineString","coordinates":[[1,2],[1,3]]}}]})");
  r = run_command({kTourmapBin, "import", "metro", loom, "--city", "lisbon", "--name", "Lisbon", "--db", live.db()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("bad.json feature 1"), std::string::npos) << r.output;

  // POIs of another city (Berlin's museums for Vienna): the error names the first one.
  auto vienna_pois_before = live.get("/api/v1/cities/vienna/pois").body;
  r = run_command({kTourmapBin, "import", "pois", data_file("poi/berlin_museums_osm_r360.js"), "--city", "vienna",
                   "--db", live.db()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("POI 0"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("outside vienna's metro network"), std::string::npos) << r.output;
  EXPECT_EQ(live.get("/api/v1/cities/vienna/pois").body, vienna_pois_before);

  // Bad usage is exit code 2.
  r = run_command({kTourmapBin, "import", "metro", loom, "--db", live.db()});
  EXPECT_EQ(r.exit_code, 2) << r.output;

  EXPECT_EQ(live.get("/api/v1/cities").body, cities_before);
  EXPECT_EQ(live.get("/api/v1/roads").body, roads_before);
  EXPECT_EQ(live.get("/api/v1/cities/lisbon/metro").body, lisbon_before);
}

TEST(ImportLive, EventsAnnounceImports) {
  LiveServer live;
  WsClient ws(live.port(), "/api/v1/events");
  auto hello = nlohmann::json::parse(ws.receive(std::chrono::seconds(5)));
  EXPECT_EQ(hello["type"], "hello");
  auto version = hello["catalog_version"].get<long long>();
  EXPECT_GT(version, 0);
  ws.send(R"({"type":"ping"})");
  EXPECT_EQ(nlohmann::json::parse(ws.receive(std::chrono::seconds(5)))["type"], "pong");
  ws.send("nonsense");
  EXPECT_EQ(nlohmann::json::parse(ws.receive(std::chrono::seconds(5)))["type"], "error");

  auto r = run_command({kTourmapBin, "import", "metro", data_file("metro/loom_freiburg.json"), "--city", "freiburg",
                        "--name", "Freiburg", "--db", live.db()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto event = nlohmann::json::parse(ws.receive(std::chrono::seconds(10)));
  EXPECT_EQ(event["type"], "catalog");
  EXPECT_GT(event["catalog_version"].get<long long>(), version);
  EXPECT_EQ(event["last_import"]["target"], "freiburg");
}

}  // namespace
}  // namespace tourmap::test
