// The read API against a real server: cities, metro, POIs, roads, caching and compression.

#include "live_server_suite.hpp"

#include "server/gzip.hpp"

#include <gtest/gtest.h>

namespace tourmap::test {
namespace {

class ReadApi : public LiveServerSuite<ReadApi> {};

TEST_F(ReadApi, HealthzAndIndex) {
  auto health = live->get_json("/healthz");
  EXPECT_EQ(health["status"], "ok");
  EXPECT_GE(health["schema_version"].get<int>(), 1);
  auto index = live->get_json("/api/v1");
  EXPECT_EQ(index["name"], "tourmap");
}

TEST_F(ReadApi, CitiesListAndDetail) {
  auto cities = live->get_json("/api/v1/cities")["cities"];
  ASSERT_EQ(cities.size(), 2u);
  EXPECT_EQ(cities[0]["id"], "lisbon");  // by name
  EXPECT_EQ(cities[0]["counts"]["stations"], 50);
  EXPECT_EQ(cities[1]["counts"]["pois"], 63);
  auto vienna = live->get_json("/api/v1/cities/vienna");
  EXPECT_EQ(vienna["lines"].size(), 5u);
  EXPECT_EQ(vienna["poi_categories"], nlohmann::json::array({"sight"}));
  EXPECT_EQ(vienna["attribution"], nlohmann::json::array({"Wiener Linien", "Stadt Wien"}));
  EXPECT_NEAR(vienna["projection"]["lon0"].get<double>(), 16.37, 0.1);
}

TEST_F(ReadApi, MetroGeoJson) {
  auto r = live->get("/api/v1/cities/lisbon/metro");
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(r.header("content-type"), "application/geo+json");
  auto fc = nlohmann::json::parse(r.body);
  EXPECT_EQ(fc["type"], "FeatureCollection");
  std::size_t stations = 0;
  for (const auto& f : fc["features"])
    if (f["properties"]["kind"] == "station") {
      ++stations;
      EXPECT_EQ(f["geometry"]["type"], "Point");
      EXPECT_FALSE(f["properties"]["lines"].empty());
    }
  EXPECT_EQ(stations, 50u);
  // A bbox around the centre keeps fewer stations.
  auto part = live->get_json("/api/v1/cities/lisbon/metro?bbox=-9.16,38.70,-9.13,38.73");
  EXPECT_LT(part["features"].size(), fc["features"].size());
  EXPECT_GT(part["features"].size(), 0u);
}

TEST_F(ReadApi, PoisWithBBoxAndPaging) {
  auto all = live->get_json("/api/v1/cities/vienna/pois");
  EXPECT_EQ(all["matched"], 63);
  EXPECT_EQ(all["attribution"], nlohmann::json::array({"Stadt Wien"}));
  EXPECT_TRUE(all["features"][0]["properties"].contains("image"));
  auto page = live->get_json("/api/v1/cities/vienna/pois?limit=10&offset=10");
  EXPECT_EQ(page["returned"], 10);
  EXPECT_EQ(page["features"][0]["id"], all["features"][10]["id"]);
  auto none = live->get_json("/api/v1/cities/lisbon/pois");
  EXPECT_EQ(none["matched"], 0);
  EXPECT_EQ(none["attribution"], nlohmann::json::array());  // always a list
  auto lisbon = live->get_json("/api/v1/cities/lisbon");
  EXPECT_TRUE(lisbon["poi_bbox"].is_null());
  auto vienna = live->get_json("/api/v1/cities/vienna");
  EXPECT_EQ(vienna["poi_bbox"].size(), 4u);
}

TEST_F(ReadApi, PoiQueryWithPolygon) {
  std::string body = R"({"within":{"type":"Polygon","coordinates":[[[16.35,48.19],[16.39,48.19],[16.39,48.22],[16.35,48.22],[16.35,48.19]]]},"limit":100})";
  auto r = http_request(live->port(), "POST", "/api/v1/cities/vienna/pois/query",
                        {{"Content-Type", "application/json"}}, body);
  ASSERT_EQ(r.status, 200) << r.body;
  auto fc = nlohmann::json::parse(r.body);
  EXPECT_GT(fc["matched"].get<int>(), 0);
  for (const auto& f : fc["features"]) {
    double lon = f["geometry"]["coordinates"][0], lat = f["geometry"]["coordinates"][1];
    EXPECT_TRUE(lon >= 16.35 && lon <= 16.39 && lat >= 48.19 && lat <= 48.22);
  }
}

TEST_F(ReadApi, RoadsListAndGeoJson) {
  auto roads = live->get_json("/api/v1/roads")["roads"];
  ASSERT_EQ(roads.size(), 2u);
  EXPECT_EQ(roads[0]["id"], "west-oakland");  // smallest first
  EXPECT_EQ(roads[0]["counts"]["edges"], 225);
  auto fc = live->get_json("/api/v1/roads/west-oakland?nodes=true");
  EXPECT_EQ(fc["edges"], 225);
  EXPECT_EQ(fc["features"].size(), 31u);
  EXPECT_TRUE(fc["features"][0]["properties"].contains("nodes"));
  auto clipped = live->get_json("/api/v1/roads/monaco?bbox=7.41,43.72,7.43,43.74");
  EXPECT_LT(clipped["edges"].get<int>(), roads[1]["counts"]["edges"].get<int>());
  EXPECT_GT(clipped["edges"].get<int>(), 0);
}

// Whether (lon, lat) lies inside the flat [lon, lat, ...] ring (even-odd).
bool inside(const nlohmann::json& ring, double lon, double lat) {
  bool in = false;
  const std::size_t n = ring.size() / 2;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const double xi = ring[2 * i], yi = ring[2 * i + 1], xj = ring[2 * j], yj = ring[2 * j + 1];
    if ((yi > lat) != (yj > lat) && lon < (xj - xi) * (lat - yi) / (yj - yi) + xi) in = !in;
  }
  return in;
}

// Monaco's context: the sea from its coastline (the open Mediterranean to the south in it, the
// Rock of Monaco-Ville and the Jardin Exotique not), parks and buildings; coarser simplification
// returns fewer points; `kinds` filters; bad parameters are refused naming the field.
TEST_F(ReadApi, RoadContextHasMonacosSea) {
  const auto context = live->get_json("/api/v1/roads/monaco/context");
  EXPECT_EQ(context["network"], "monaco");
  EXPECT_FALSE(context["attribution"].get<std::string>().empty());
  std::size_t seas = 0, parks = 0, buildings = 0;
  bool open_sea = false, rock = false, garden = false;
  for (const auto& a : context["areas"]) {
    const auto kind = a["kind"].get<std::string>();
    ASSERT_FALSE(a["rings"].empty());
    for (const auto& ring : a["rings"]) ASSERT_GE(ring.size(), 6u);
    if (kind == "park") ++parks;
    if (kind == "building") ++buildings;
    if (kind != "sea") continue;
    ++seas;
    open_sea = open_sea || inside(a["rings"][0], 7.43, 43.60);
    rock = rock || inside(a["rings"][0], 7.4230, 43.7310);
    garden = garden || inside(a["rings"][0], 7.4150, 43.7312);
  }
  EXPECT_GE(seas, 1u);
  EXPECT_TRUE(open_sea);
  EXPECT_FALSE(rock);
  EXPECT_FALSE(garden);
  EXPECT_GT(parks, 0u);
  EXPECT_GT(buildings, 100u);

  const auto coarse = live->get_json("/api/v1/roads/monaco/context?simplify_m=50");
  EXPECT_LT(coarse["points"].get<std::size_t>(), context["points"].get<std::size_t>() / 2);
  const auto sea_only = live->get_json("/api/v1/roads/monaco/context?kinds=sea");
  ASSERT_GE(sea_only["areas"].size(), 1u);
  for (const auto& a : sea_only["areas"]) EXPECT_EQ(a["kind"], "sea");
  EXPECT_TRUE(sea_only["lines"].empty());
  EXPECT_TRUE(sea_only["places"].empty());

  const auto unknown = live->get("/api/v1/roads/monaco/context?kinds=sea,lava");
  EXPECT_EQ(unknown.status, 400);
  EXPECT_EQ(nlohmann::json::parse(unknown.body)["error"]["field"], "kinds") << unknown.body;
  const auto far = live->get("/api/v1/roads/monaco/context?simplify_m=1e9");
  EXPECT_EQ(far.status, 400);
  EXPECT_EQ(nlohmann::json::parse(far.body)["error"]["field"], "simplify_m") << far.body;
  EXPECT_EQ(live->get("/api/v1/roads/atlantis/context").status, 404);
}

TEST_F(ReadApi, GzipWhenAccepted) {
  auto plain = live->get("/api/v1/roads/monaco");
  auto packed = live->get("/api/v1/roads/monaco", {{"Accept-Encoding", "gzip"}});
  ASSERT_EQ(packed.status, 200);
  EXPECT_EQ(packed.header("content-encoding"), "gzip");
  EXPECT_EQ(plain.header("content-encoding"), "");
  EXPECT_LT(packed.body.size(), plain.body.size() / 3);
  EXPECT_EQ(server::gzip_decompress(packed.body), plain.body);
  EXPECT_EQ(packed.header("vary"), "Accept-Encoding");
}

TEST_F(ReadApi, EtagRevalidationAndHead) {
  auto first = live->get("/api/v1/cities/vienna/metro");
  auto etag = first.header("etag");
  ASSERT_FALSE(etag.empty());
  auto again = live->get("/api/v1/cities/vienna/metro", {{"If-None-Match", etag}});
  EXPECT_EQ(again.status, 304);
  EXPECT_TRUE(again.body.empty());
  auto head = http_request(live->port(), "HEAD", "/api/v1/cities/vienna/metro");
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(head.header("content-length"), std::to_string(first.body.size()));
}

TEST_F(ReadApi, StaticFilesAndTraversal) {
  auto index = live->get("/");
  EXPECT_EQ(index.status, 200);
  EXPECT_EQ(index.header("content-type"), "text/html; charset=utf-8");
  EXPECT_EQ(index.header("cache-control"), "no-cache");
  auto js = live->get("/assets/app-abc.js");
  EXPECT_EQ(js.header("content-type"), "text/javascript; charset=utf-8");
  EXPECT_NE(js.header("cache-control").find("immutable"), std::string::npos);
  for (std::string target : {"/../outside.txt", "/%2e%2e/outside.txt", "/assets/..%2f..%2foutside.txt",
                             "/..%5coutside.txt", "/%2e%2e%2f%2e%2e%2fetc%2fpasswd", "/web/../outside.txt"}) {
    auto r = live->get(target);
    EXPECT_TRUE(r.status == 404 || r.status == 400) << target << " -> " << r.status;
    EXPECT_EQ(r.body.find("secret"), std::string::npos) << target;
    EXPECT_EQ(r.body.find("root:"), std::string::npos) << target;
  }
}

TEST_F(ReadApi, MetricsCountRequestsByRoute) {
  live->get("/api/v1/cities/vienna");
  live->get("/api/v1/cities/nope");
  auto text = live->get("/metrics").body;
  EXPECT_NE(text.find(R"(tourmap_http_requests_total{route="/api/v1/cities/{id}",method="GET",status="200"})"),
            std::string::npos);
  EXPECT_NE(text.find(R"(tourmap_http_requests_total{route="/api/v1/cities/{id}",method="GET",status="404"})"),
            std::string::npos);
  EXPECT_NE(text.find("tourmap_http_request_duration_seconds_bucket"), std::string::npos);
  EXPECT_NE(text.find("tourmap_compute_queued"), std::string::npos);
}

TEST_F(ReadApi, SpecIsServed) {
  auto r = live->get("/api/v1/openapi.yaml");
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.body.rfind("openapi: 3", 0), 0u);
}

}  // namespace
}  // namespace tourmap::test
