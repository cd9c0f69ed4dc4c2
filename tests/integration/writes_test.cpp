// The write endpoints against a real server: API keys (missing, wrong, revoked), imports by
// upload (roads, metro, POIs), failed imports that change nothing, deletes, cache purge, the
// upload limit, and X-Forwarded-For from a trusted proxy.

#include "live_server.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace tourmap::test {
namespace {

TEST(Writes, NeedAValidApiKey) {
  LiveServer live;
  const std::string monaco = file_bytes(data_file("roads/monaco.osm.gz"));
  auto r = http_request(live.port(), "PUT", "/api/v1/roads/monaco2?name=M", {}, monaco);
  EXPECT_EQ(r.status, 401);
  EXPECT_EQ(error_of(r)["code"], "unauthorized");
  EXPECT_EQ(error_of(r)["field"], "Authorization");
  EXPECT_NE(r.header("www-authenticate").find("Bearer"), std::string::npos);

  const std::string key = create_key(live);
  std::string wrong = key;
  wrong.back() = wrong.back() == 'a' ? 'b' : 'a';
  for (const auto& headers : std::vector<std::map<std::string, std::string>>{
           bearer(wrong), {{"X-API-Key", wrong}}, {{"Authorization", "Basic dXNlcjpwYXNz"}}, bearer("tm_garbage")}) {
    r = http_request(live.port(), "DELETE", "/api/v1/roads/monaco", headers);
    EXPECT_EQ(r.status, 401) << r.body;
    EXPECT_EQ(error_of(r)["code"], headers.count("Authorization") && headers.at("Authorization").rfind("Basic", 0) == 0
                                       ? "unauthorized"
                                       : "invalid_api_key");
  }
  EXPECT_EQ(live.get("/api/v1/roads/monaco").status, 200);  // nothing was deleted

  // Both header forms work; a revoked key stops working at once.
  r = http_request(live.port(), "DELETE", "/api/v1/cache", {{"X-API-Key", key}});
  EXPECT_EQ(r.status, 200) << r.body;
  r = http_request(live.port(), "DELETE", "/api/v1/cache", bearer(key));
  EXPECT_EQ(r.status, 200) << r.body;
  auto id = key.substr(3, 16);
  auto revoked = run_command({kTourmapBin, "keys", "revoke", id, "--db", live.db()});
  ASSERT_EQ(revoked.exit_code, 0) << revoked.output;
  r = http_request(live.port(), "DELETE", "/api/v1/cache", bearer(key));
  EXPECT_EQ(r.status, 401);
  auto listed = run_command({kTourmapBin, "keys", "list", "--db", live.db()});
  EXPECT_NE(listed.output.find("revoked"), std::string::npos) << listed.output;
  EXPECT_EQ(listed.output.find(key.substr(20)), std::string::npos);  // the secret is never shown again

  // Reads stay open.
  EXPECT_EQ(live.get("/api/v1/roads").status, 200);
}

TEST(Writes, ImportRoadsByUploadThenDelete) {
  LiveServer live;
  const auto key = create_key(live);
  const std::string bytes = file_bytes(data_file("roads/berlin-siegessaeule.osm.gz"));
  auto r = http_request(live.port(), "PUT", "/api/v1/roads/tiergarten?name=Tiergarten", bearer(key), bytes);
  ASSERT_EQ(r.status, 200) << r.body;
  auto result = nlohmann::json::parse(r.body);
  EXPECT_EQ(result["kind"], "roads");
  EXPECT_EQ(result["target"], "tiergarten");
  EXPECT_FALSE(result["skipped"]);
  EXPECT_GT(result["rows"].get<int>(), 2000);
  auto net_name = [&] {
    const auto list = live.get_json("/api/v1/roads");
    for (const auto& net : list["roads"])
      if (net["id"] == "tiergarten") return net["name"].get<std::string>() + " " + net["counts"]["edges"].dump();
    return std::string("missing");
  };
  EXPECT_EQ(net_name(), "Tiergarten 1142");

  // The same bytes again: nothing to do, unless forced.
  r = http_request(live.port(), "PUT", "/api/v1/roads/tiergarten", bearer(key), bytes);
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_TRUE(nlohmann::json::parse(r.body)["skipped"]);
  r = http_request(live.port(), "PUT", "/api/v1/roads/tiergarten?force=true", bearer(key), bytes);
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_GT(nlohmann::json::parse(r.body)["version"].get<long>(), result["version"].get<long>());
  EXPECT_EQ(net_name(), "Tiergarten 1142");  // the name is kept without ?name

  r = http_request(live.port(), "DELETE", "/api/v1/roads/tiergarten", bearer(key));
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(live.get("/api/v1/roads/tiergarten").status, 404);
  r = http_request(live.port(), "DELETE", "/api/v1/roads/tiergarten", bearer(key));
  EXPECT_EQ(r.status, 404);
}

TEST(Writes, FailedImportsChangeNothing) {
  LiveServer live;
  const auto key = create_key(live);
  auto monaco = [&] { return live.get_json("/api/v1/roads")["roads"][1]; };  // smallest first
  const auto before = monaco();
  ASSERT_EQ(before["id"], "monaco");
  // A truncated extract: the loader fails half way; the stored network stays as it was.
  std::string truncated = file_bytes(data_file("roads/monaco.osm.gz"));
  truncated.resize(truncated.size() / 2);
  auto r = http_request(live.port(), "PUT", "/api/v1/roads/monaco?force=true", bearer(key), truncated);
  EXPECT_EQ(r.status, 422) << r.body;
  EXPECT_EQ(error_of(r)["code"], "invalid_source");
  EXPECT_EQ(error_of(r)["field"], "body");
  EXPECT_EQ(monaco(), before);

  r = http_request(live.port(), "PUT", "/api/v1/roads/x?name=X", bearer(key), "name,lon,lat\n");
  EXPECT_EQ(r.status, 415);
  r = http_request(live.port(), "PUT", "/api/v1/roads/x?name=X", bearer(key), "");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(error_of(r)["field"], "body");
  r = http_request(live.port(), "PUT", "/api/v1/roads/Bad%20Id?name=X", bearer(key), "<osm version='0.6'/>");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(error_of(r)["field"], "id");
  r = http_request(live.port(), "PUT", "/api/v1/roads/newnet", bearer(key), "<osm version='0.6'/>");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(error_of(r)["field"], "name");

  // POIs: the city must exist; a CSV without coordinates names its problem; Vienna keeps its 63.
  r = http_request(live.port(), "PUT", "/api/v1/cities/atlantis/pois", bearer(key), "name,lon,lat\nA,1,2\n");
  EXPECT_EQ(r.status, 404);
  r = http_request(live.port(), "PUT", "/api/v1/cities/vienna/pois", bearer(key), "name,lat\nAlbertina,48.2\n");
  EXPECT_EQ(r.status, 422) << r.body;
  EXPECT_NE(error_of(r)["message"].get<std::string>().find("lon"), std::string::npos) << r.body;
  EXPECT_EQ(live.get_json("/api/v1/cities/vienna/pois")["matched"], 63);

  // Metro: station-csvs needs its three parts; an unknown format is named.
  r = http_request(live.port(), "PUT", "/api/v1/cities/london/metro?format=station-csvs&name=London",
                   {{"X-API-Key", key}, {"Content-Type", "application/json"}}, R"({"stations": "id,name\n"})");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(error_of(r)["field"], "lines");
  r = http_request(live.port(), "PUT", "/api/v1/cities/london/metro?format=kml&name=London", bearer(key), "{}");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(error_of(r)["field"], "format");
  r = http_request(live.port(), "PUT", "/api/v1/cities/london/metro?name=London", bearer(key), "{\"type\": 1}");
  EXPECT_EQ(r.status, 422) << r.body;
  EXPECT_EQ(live.get("/api/v1/cities/london").status, 404);
}

TEST(Writes, ImportCityByUploadThenDelete) {
  LiveServer live;
  const auto key = create_key(live);
  auto r = http_request(live.port(), "PUT", "/api/v1/cities/freiburg/metro?name=Freiburg&attribution=VAG", bearer(key),
                        file_bytes(data_file("metro/loom_freiburg.json")));
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NE(nlohmann::json::parse(r.body)["summary"].get<std::string>().find("74 stations"), std::string::npos);
  r = http_request(live.port(), "PUT", "/api/v1/cities/freiburg/pois?category=sight", bearer(key),
                   "name,lon,lat\nMuenster,7.8529,47.9956\nSchwabentor,7.8560,47.9918\n");
  ASSERT_EQ(r.status, 200) << r.body;
  auto pois = live.get_json("/api/v1/cities/freiburg/pois");
  EXPECT_EQ(pois["matched"], 2);
  EXPECT_EQ(live.get_json("/api/v1/cities/freiburg")["name"], "Freiburg");

  // London from its three CSVs in one JSON body.
  nlohmann::json parts = {{"stations", file_bytes(data_file("metro/london.stations.csv"))},
                          {"lines", file_bytes(data_file("metro/london.lines.csv"))},
                          {"connections", file_bytes(data_file("metro/london.connections.csv"))}};
  r = http_request(live.port(), "PUT", "/api/v1/cities/london/metro?format=station-csvs&name=London",
                   {{"X-API-Key", key}, {"Content-Type", "application/json"}}, parts.dump());
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(live.get_json("/api/v1/cities/london")["counts"]["stations"], 302);

  r = http_request(live.port(), "DELETE", "/api/v1/cities/freiburg", bearer(key));
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(live.get("/api/v1/cities/freiburg").status, 404);
  EXPECT_EQ(live.get("/api/v1/cities/freiburg/pois").status, 404);
}

TEST(Writes, ImportCityFromAnOsmExtract) {
  // Issue 16: a city's transit network from the route relations of an extract and its POIs
  // from its tourist places, both uploaded as the .osm.pbf bytes.
  LiveServer live;
  const auto key = create_key(live);
  const std::string bytes = file_bytes(data_file("roads/liechtenstein-latest.osm.pbf"));
  auto r = http_request(live.port(), "PUT", "/api/v1/cities/li/metro?format=osm&modes=train,bus&name=Liechtenstein",
                        bearer(key), bytes);
  ASSERT_EQ(r.status, 200) << r.body;
  const auto summary = nlohmann::json::parse(r.body)["summary"].get<std::string>();
  EXPECT_NE(summary.find("OSM train, bus: 20 routes"), std::string::npos) << summary;
  const auto city = live.get_json("/api/v1/cities/li");
  EXPECT_GE(city["counts"]["stations"].get<int>(), 20);
  EXPECT_EQ(city["counts"]["lines"], 16);  // 2 train lines (REX, S2), 14 bus lines
  r = http_request(live.port(), "PUT", "/api/v1/cities/li/pois", bearer(key), bytes);
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(live.get_json("/api/v1/cities/li/pois")["matched"], 26);
  // The layout of a network from OSM: octilinear, nothing added.
  const auto layout = live.get_json("/api/v1/cities/li/layout");
  EXPECT_EQ(layout["quality"]["octilinear_share"], 1.0);
  EXPECT_EQ(layout["quality"]["added_crossings"], 0);

  // An unknown mode and a body that is no extract: 4xx naming the field, nothing imported.
  r = http_request(live.port(), "PUT", "/api/v1/cities/li2/metro?format=osm&modes=bus,zeppelin&name=X", bearer(key), bytes);
  EXPECT_EQ(r.status, 400) << r.body;
  EXPECT_EQ(nlohmann::json::parse(r.body)["error"]["field"], "modes");
  r = http_request(live.port(), "PUT", "/api/v1/cities/li2/metro?format=osm&name=X", bearer(key), "not osm");
  EXPECT_EQ(r.status, 415) << r.body;
  r = http_request(live.port(), "PUT", "/api/v1/cities/li2/metro?format=osm&modes=ferry&name=X", bearer(key), bytes);
  EXPECT_EQ(r.status / 100, 4) << r.body;  // no ferry route in the extract
  EXPECT_EQ(live.get("/api/v1/cities/li2").status, 404);
}

TEST(Writes, UploadLimitAppliesOnlyWithAKey) {
  // A body limit below the extract's size: with a key the upload limit applies instead.
  LiveServer live({"--max-body", "100000", "--max-upload", "300000"});
  const auto key = create_key(live);
  const std::string bytes = file_bytes(data_file("roads/berlin-siegessaeule.osm.gz"));  // ~190 KB
  ASSERT_GT(bytes.size(), 100000u);
  auto r = http_request(live.port(), "PUT", "/api/v1/roads/tiergarten?name=T", {}, bytes);
  EXPECT_EQ(r.status, 401);  // refused for the missing key, not for the size
  r = http_request(live.port(), "PUT", "/api/v1/roads/tiergarten?name=T", bearer(key), bytes);
  EXPECT_EQ(r.status, 200) << r.body;
  r = http_request(live.port(), "PUT", "/api/v1/roads/monaco?force=true", bearer(key),
                   file_bytes(data_file("roads/monaco.osm.gz")));  // ~330 KB
  EXPECT_EQ(r.status, 413);
  EXPECT_NE(error_of(r)["message"].get<std::string>().find("300000"), std::string::npos) << r.body;
  // Reads keep the ordinary body limit.
  r = http_request(live.port(), "POST", "/api/v1/deform/focus", {{"Content-Type", "application/json"}},
                   std::string(150000, ' '));
  EXPECT_EQ(r.status, 413);
}

TEST(Writes, ExpectContinueIsAnsweredBeforeTheUpload) {
  LiveServer live;
  const auto key = create_key(live);
  const std::string head = "PUT /api/v1/roads/big?name=Big HTTP/1.1\r\nHost: t\r\nContent-Length: 5000000\r\n"
                           "Expect: 100-continue\r\n";
  // Without a key: 401 at once; the 5 MB are never sent.
  auto answer = raw_exchange(live.port(), head + "\r\n", std::chrono::milliseconds(3000));
  EXPECT_EQ(answer.rfind("HTTP/1.1 401", 0), 0u) << answer;
  EXPECT_EQ(answer.find("100 Continue"), std::string::npos) << answer;
  // With one: 100 Continue, then the server waits for the body.
  answer = raw_exchange(live.port(), head + "X-API-Key: " + key + "\r\n\r\n", std::chrono::milliseconds(1000));
  EXPECT_EQ(answer.rfind("HTTP/1.1 100 Continue", 0), 0u) << answer;
}

TEST(Writes, DeleteIsPushedToEventSubscribers) {
  LiveServer live;
  const auto key = create_key(live);
  WsClient events(live.port(), "/api/v1/events");
  auto hello = nlohmann::json::parse(events.receive(std::chrono::seconds(5)));
  EXPECT_EQ(hello["type"], "hello");
  auto r = http_request(live.port(), "DELETE", "/api/v1/roads/west-oakland", bearer(key));
  ASSERT_EQ(r.status, 200) << r.body;
  auto ev = nlohmann::json::parse(events.receive(std::chrono::seconds(10)));
  EXPECT_EQ(ev["type"], "catalog");
}

TEST(Writes, ForwardedForCountsOnlyFromTrustedProxies) {
  // One request per second, burst 2: the third request from one client is refused.
  LiveServer live({"--rate-limit", "1", "--rate-burst", "2", "--trusted-proxies", "127.0.0.1"});
  auto from = [&](const std::string& client) {
    return live.get("/api/v1/cities", {{"X-Forwarded-For", client}}).status;
  };
  EXPECT_EQ(from("203.0.113.1"), 200);
  EXPECT_EQ(from("203.0.113.1"), 200);
  EXPECT_EQ(from("203.0.113.1"), 429);
  EXPECT_EQ(from("203.0.113.2"), 200);  // another client behind the same proxy has its own bucket
  // A client cannot pick its bucket by writing its own X-Forwarded-For in front of the proxy's.
  EXPECT_EQ(from("198.51.100.1, 203.0.113.1"), 429);

  LiveServer untrusted({"--rate-limit", "1", "--rate-burst", "2"});
  auto via = [&](const std::string& client) {
    return untrusted.get("/api/v1/cities", {{"X-Forwarded-For", client}}).status;
  };
  EXPECT_EQ(via("203.0.113.1"), 200);
  EXPECT_EQ(via("203.0.113.2"), 200);
  EXPECT_EQ(via("203.0.113.3"), 429);  // the header is ignored: all three are 127.0.0.1
}

}  // namespace
}  // namespace tourmap::test
