// Whole cities from an OSM extract alone (issue 16, part 4) against a real server:
// PUT /cities/{id}/source imports the transit network, the POIs, the roads and the context
// layers in one transaction, announces its stages on WS /api/v1/events, changes nothing when
// sent twice, and nothing at all when any part of the source is bad.

#include "live_server.hpp"
#include "temp_dir.hpp"
#include "zip_file.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tourmap::test {
namespace {

// The stages of the import_progress events received until "done" (catalog events skipped).
std::vector<std::string> progress_stages(WsClient& events, const std::string& city) {
  std::vector<std::string> stages;
  while (stages.empty() || stages.back() != "done") {
    auto ev = nlohmann::json::parse(events.receive(std::chrono::seconds(10)));
    if (ev["type"] != "import_progress") continue;
    EXPECT_EQ(ev["city"], city);
    EXPECT_EQ(ev["step"].get<std::size_t>(), stages.size() + 1);
    EXPECT_EQ(ev["steps"], 5);
    stages.push_back(ev["stage"]);
  }
  return stages;
}

// The road network's entry in GET /api/v1/roads (its counts, version, attribution).
nlohmann::json road_summary(const LiveServer& live, const std::string& id) {
  const auto list = live.get_json("/api/v1/roads");  // held: a range-for over a temporary's member dangles
  for (const auto& r : list["roads"])
    if (r["id"] == id) return r;
  ADD_FAILURE() << "no road network " << id << " in " << list.dump();
  return nlohmann::json::object();
}

std::string multipart(const std::string& boundary, const std::vector<std::pair<std::string, std::string>>& parts) {
  std::string body;
  for (const auto& [name, bytes] : parts)
    body += "--" + boundary + "\r\nContent-Disposition: form-data; name=\"" + name + "\"; filename=\"" + name +
            ".bin\"\r\nContent-Type: application/octet-stream\r\n\r\n" + bytes + "\r\n";
  return body + "--" + boundary + "--\r\n";
}

std::map<std::string, std::string> with_type(std::map<std::string, std::string> headers, const std::string& type) {
  headers["Content-Type"] = type;
  return headers;
}

TEST(CitySource, LiechtensteinFromItsExtractAlone) {
  LiveServer live;
  const auto key = create_key(live);
  WsClient events(live.port(), "/api/v1/events");
  EXPECT_EQ(nlohmann::json::parse(events.receive(std::chrono::seconds(5)))["type"], "hello");
  const std::string bytes = file_bytes(data_file("roads/liechtenstein-latest.osm.pbf"));
  auto r = http_request(live.port(), "PUT", "/api/v1/cities/li/source?name=Liechtenstein&modes=train,bus",
                        bearer(key), bytes);
  ASSERT_EQ(r.status, 200) << r.body;
  const auto imports = nlohmann::json::parse(r.body)["imports"];
  ASSERT_EQ(imports.size(), 3u) << r.body;
  EXPECT_EQ(imports[0]["kind"], "metro");
  EXPECT_EQ(imports[1]["kind"], "pois");
  EXPECT_EQ(imports[2]["kind"], "roads");
  EXPECT_EQ(progress_stages(events, "li"), (std::vector<std::string>{"transit", "pois", "roads", "writing", "done"}));

  // One extract gave the city, its POIs, and a road network of the same id with context layers.
  const auto city = live.get_json("/api/v1/cities/li");
  EXPECT_GE(city["counts"]["stations"].get<int>(), 20);
  EXPECT_EQ(city["counts"]["lines"], 16);
  EXPECT_EQ(live.get_json("/api/v1/cities/li/pois")["matched"], 26);
  EXPECT_NE(city.dump().find("OpenStreetMap"), std::string::npos) << city.dump();
  const auto roads = road_summary(live, "li");
  EXPECT_GT(roads["counts"]["edges"].get<int>(), 1000) << roads.dump();
  EXPECT_NE(roads["attribution"].dump().find("OpenStreetMap"), std::string::npos) << roads.dump();
  const auto context = live.get_json("/api/v1/roads/li/context");
  EXPECT_GT(context["areas"].size(), 1000u);  // Liechtenstein: woods, parks, buildings, water
  EXPECT_GT(context["places"].size(), 10u);
  const auto layout = live.get_json("/api/v1/cities/li/layout");
  EXPECT_EQ(layout["quality"]["octilinear_share"], 1.0);
  EXPECT_EQ(live.get("/api/v1/cities/li/clusters?zoom=1").status, 200);

  // The same source again changes nothing.
  r = http_request(live.port(), "PUT", "/api/v1/cities/li/source?modes=train,bus", bearer(key), bytes);
  ASSERT_EQ(r.status, 200) << r.body;
  const auto again = nlohmann::json::parse(r.body);
  ASSERT_EQ(again["imports"].size(), 3u) << r.body;
  for (const auto& imp : again["imports"]) EXPECT_TRUE(imp["skipped"].get<bool>()) << r.body;
  EXPECT_EQ(live.get_json("/api/v1/cities/li")["version"], city["version"]);
}

TEST(CitySource, MonacoBusesByDefault) {
  // No rail route in Monaco's extract: the default modes fall back to its buses. (The sample
  // data has Monaco as "monaco" already; a new id imports it again.)
  LiveServer live;
  const auto key = create_key(live);
  auto r = http_request(live.port(), "PUT", "/api/v1/cities/mc/source?name=Monaco", bearer(key),
                        file_bytes(data_file("roads/monaco.osm.gz")));
  ASSERT_EQ(r.status, 200) << r.body;
  const auto summary = nlohmann::json::parse(r.body)["imports"][0]["summary"].get<std::string>();
  EXPECT_NE(summary.find("OSM bus"), std::string::npos) << summary;
  const auto city = live.get_json("/api/v1/cities/mc");
  EXPECT_GE(city["counts"]["lines"].get<int>(), 5) << city.dump();
  EXPECT_GE(city["counts"]["stations"].get<int>(), 30) << city.dump();
  EXPECT_GT(city["counts"]["pois"].get<int>(), 5) << city.dump();
  EXPECT_EQ(live.get_json("/api/v1/cities/mc/layout")["quality"]["octilinear_share"], 1.0);
  EXPECT_EQ(live.get("/api/v1/roads/mc").status, 200);
}

// A small feed for Liechtenstein: bus 11 from Schaan over Vaduz to Balzers, both directions.
std::map<std::string, std::string> liechtenstein_feed(const std::string& last_stop = "balzers") {
  return {{"stops.txt", "stop_id,stop_name,stop_lat,stop_lon\nschaan,Schaan Bahnhof,47.1656,9.5094\n"
                        "vaduz,Vaduz Post,47.1399,9.5215\nbalzers,Balzers Zentrum,47.0667,9.5028\n"},
          {"routes.txt", "route_id,route_short_name,route_type,route_color\n11,11,3,E2001A\n"},
          {"trips.txt", "route_id,service_id,trip_id\n11,d,t1\n11,d,t2\n"},
          {"stop_times.txt", "trip_id,arrival_time,departure_time,stop_id,stop_sequence\n"
                             "t1,08:00:00,08:00:00,schaan,1\nt1,08:10:00,08:10:00,vaduz,2\nt1,08:25:00,08:25:00," +
                                 last_stop + ",3\nt2,09:00:00,09:00:00,balzers,1\nt2,09:15:00,09:15:00,vaduz,2\n"}};
}

TEST(CitySource, TransitFromAGtfsFeedTheRestFromTheExtract) {
  LiveServer live;
  const auto key = create_key(live);
  test::TempDir dir;
  const std::string osm = file_bytes(data_file("roads/liechtenstein-latest.osm.pbf"));
  const std::string b = "tourmap-test-boundary";
  const auto headers = with_type(bearer(key), "multipart/form-data; boundary=" + b);
  auto r = http_request(live.port(), "PUT", "/api/v1/cities/lif/source?name=Liechtenstein", headers,
                        multipart(b, {{"osm", osm}, {"gtfs", file_bytes(write_zip(dir, "feed.zip", liechtenstein_feed()))}}));
  ASSERT_EQ(r.status, 200) << r.body;
  const auto summary = nlohmann::json::parse(r.body)["imports"][0]["summary"].get<std::string>();
  EXPECT_NE(summary.find("GTFS bus: 1 of 1 routes"), std::string::npos) << summary;
  const auto city = live.get_json("/api/v1/cities/lif");
  EXPECT_EQ(city["counts"]["stations"], 3);
  EXPECT_EQ(city["counts"]["lines"], 1);
  EXPECT_EQ(city["counts"]["pois"], 26);
  // Credits: the feed for the transit (its agency.txt is not read), OpenStreetMap for the POIs.
  EXPECT_NE(city["attribution"].dump().find("GTFS feed"), std::string::npos) << city["attribution"];
  EXPECT_NE(city["attribution"].dump().find("OpenStreetMap"), std::string::npos) << city["attribution"];
  EXPECT_EQ(live.get("/api/v1/roads/lif").status, 200);

  // A feed naming an unknown stop: 422 naming the file and row; nothing changes.
  r = http_request(live.port(), "PUT", "/api/v1/cities/lif/source?force=true", headers,
                   multipart(b, {{"osm", osm}, {"gtfs", file_bytes(write_zip(dir, "bad.zip", liechtenstein_feed("nowhere")))}}));
  EXPECT_EQ(r.status, 422) << r.body;
  EXPECT_NE(error_of(r)["message"].get<std::string>().find("stop_times.txt row 4"), std::string::npos) << r.body;
  EXPECT_EQ(live.get_json("/api/v1/cities/lif")["version"], city["version"]);
}

TEST(CitySource, BadSourcesChangeNothing) {
  LiveServer live;
  const auto key = create_key(live);
  const std::string bytes = file_bytes(data_file("roads/liechtenstein-latest.osm.pbf"));
  auto r = http_request(live.port(), "PUT", "/api/v1/cities/li/source?name=Liechtenstein&modes=train", bearer(key),
                        bytes);
  ASSERT_EQ(r.status, 200) << r.body;
  const auto city_version = live.get_json("/api/v1/cities/li")["version"];
  const auto city_counts = live.get_json("/api/v1/cities/li")["counts"];
  const auto roads_version = road_summary(live, "li")["version"];
  ASSERT_TRUE(roads_version.is_number());

  // A damaged extract (cut in half) fails in some part; nothing of the city or its roads changes.
  r = http_request(live.port(), "PUT", "/api/v1/cities/li/source?modes=train,bus&force=true", bearer(key),
                   bytes.substr(0, bytes.size() / 2));
  EXPECT_EQ(r.status, 422) << r.body;
  EXPECT_NE(error_of(r)["message"].get<std::string>().find("nothing was imported"), std::string::npos) << r.body;
  EXPECT_EQ(live.get_json("/api/v1/cities/li")["version"], city_version);
  EXPECT_EQ(road_summary(live, "li")["version"], roads_version);
  EXPECT_EQ(live.get_json("/api/v1/cities/li")["counts"], city_counts);

  // Requests naming what is wrong, never a 500.
  struct Case {
    std::string target, content_type, body;
    int status;
    std::string field;
  };
  const std::string b = "b0undary";
  const std::string mp = "multipart/form-data; boundary=" + b;
  const std::vector<Case> cases = {
      {"/api/v1/cities/new/source?name=N", "", "", 400, "body"},
      {"/api/v1/cities/new/source", "", bytes, 400, "name"},
      {"/api/v1/cities/Bad%20Id/source?name=N", "", bytes, 400, "id"},
      {"/api/v1/cities/new/source?name=N&modes=zeppelin", "", bytes, 400, "modes"},
      {"/api/v1/cities/new/source?name=N", "", "not an extract", 415, "osm"},
      {"/api/v1/cities/new/source?name=N", mp, multipart(b, {{"osm", bytes}, {"gtfs", "not a zip"}}), 415, "gtfs"},
      {"/api/v1/cities/new/source?name=N", mp, multipart(b, {{"gtfs", "PK\x03\x04zip"}}), 400, "osm"},
      {"/api/v1/cities/new/source?name=N", mp, multipart(b, {{"osm", bytes}, {"pictures", "x"}}), 400, "body"},
      {"/api/v1/cities/new/source?name=N", mp, multipart(b, {{"osm", bytes}, {"osm", bytes}}), 400, "osm"},
      {"/api/v1/cities/new/source?name=N", mp, "--" + b + "\r\nContent-Disposition: form-data; name=\"osm\"\r\n\r\nxx",
       400, "body"},
      {"/api/v1/cities/new/source?name=N", "multipart/form-data", multipart(b, {{"osm", bytes}}), 400, "body"},
      {"/api/v1/cities/new/source?name=N&modes=ferry", "", bytes, 422, "body"},
  };
  for (const auto& c : cases) {
    auto headers = c.content_type.empty() ? bearer(key) : with_type(bearer(key), c.content_type);
    r = http_request(live.port(), "PUT", c.target, headers, c.body);
    EXPECT_EQ(r.status, c.status) << c.target << " " << c.content_type << ": " << r.body;
    if (r.status / 100 == 4) {
      EXPECT_EQ(error_of(r)["field"], c.field) << c.target << ": " << r.body;
    }
  }
  EXPECT_EQ(live.get("/api/v1/cities/new").status, 404);
  EXPECT_EQ(live.get("/api/v1/roads/new").status, 404);
}

}  // namespace
}  // namespace tourmap::test
