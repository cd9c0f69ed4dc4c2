// GET /api/v1/cities/{id}/layout/roads against a real server (issue 16, item 6): Liechtenstein's
// transit network and roads uploaded from its OSM extract under one id, and Monaco's bus
// network beside the server's Monaco roads; the streets come back in the layout's frame with
// every guided station on its street, cached; a city without roads is a 404, a bad parameter a
// 400.

#include "live_server_suite.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tourmap::test {
namespace {

class SchematicRoads : public LiveServerSuite<SchematicRoads> {
 protected:
  static void SetUpTestSuite() {
    LiveServerSuite::SetUpTestSuite();
    const auto key = create_key(*live);
    const std::string extract = file_bytes(data_file("roads/liechtenstein-latest.osm.pbf"));
    auto r = http_request(live->port(), "PUT", "/api/v1/cities/liechtenstein/metro?format=osm&modes=train,bus&name=Liechtenstein",
                          bearer(key), extract);
    ASSERT_EQ(r.status, 200) << r.body;
    r = http_request(live->port(), "PUT", "/api/v1/roads/liechtenstein?name=Liechtenstein", bearer(key), extract);
    ASSERT_EQ(r.status, 200) << r.body;
    // Monaco's buses; its roads are the server's "monaco" network already.
    r = http_request(live->port(), "PUT", "/api/v1/cities/monaco/metro?format=osm&modes=bus&name=Monaco", bearer(key),
                     file_bytes(data_file("roads/monaco.osm.gz")));
    ASSERT_EQ(r.status, 200) << r.body;
  }
};

struct Point {
  double x, y;
};

double segment_distance(Point p, Point a, Point b) {
  const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  const double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

// Per station of the layout: the distance from its layout position to the nearest warped road.
std::vector<double> station_to_road(const nlohmann::json& layout, const nlohmann::json& roads) {
  std::vector<double> out;
  for (const auto& f : layout["stations"]["features"]) {
    const Point s{f["geometry"]["coordinates"][0].get<double>(), f["geometry"]["coordinates"][1].get<double>()};
    double best = 1e300;
    for (const auto& [cls, lines] : roads["roads"].items())
      for (const auto& line : lines)
        for (std::size_t i = 2; i + 1 < line.size(); i += 2)
          best = std::min(best, segment_distance(s, {line[i - 2].get<double>(), line[i - 1].get<double>()},
                                                 {line[i].get<double>(), line[i + 1].get<double>()}));
    out.push_back(best);
  }
  return out;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * (v.size() - 1))];
}

// The layout's mean edge length in its frame: the scale station gaps are judged by.
double mean_edge(const nlohmann::json& layout) {
  double sum = 0;
  const auto& edges = layout["edges"]["features"];
  for (const auto& e : edges) {
    const auto& c = e["geometry"]["coordinates"];
    for (std::size_t i = 1; i < c.size(); ++i)
      sum += std::hypot(c[i][0].get<double>() - c[i - 1][0].get<double>(), c[i][1].get<double>() - c[i - 1][1].get<double>());
  }
  return sum / static_cast<double>(edges.size());
}

TEST_F(SchematicRoads, LiechtensteinStationsSitOnTheirStreets) {
  const auto layout = live->get_json("/api/v1/cities/liechtenstein/layout");
  const auto r = live->get("/api/v1/cities/liechtenstein/layout/roads");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.header("x-result-cache"), "miss");
  const auto roads = nlohmann::json::parse(r.body);
  const auto& stats = roads["stats"];
  EXPECT_EQ(roads["frame"], "layout");
  EXPECT_EQ(roads["road_network"]["id"], "liechtenstein");
  EXPECT_GT(roads["roads"]["major"].size(), 10u);
  EXPECT_GT(roads["roads"]["minor"].size(), 500u);
  EXPECT_GT(stats["road_edges"].get<int>(), 5000);
  const auto stations = layout["stations"]["features"].size();
  EXPECT_EQ(stats["stations"].get<std::size_t>(), stations);
  EXPECT_GE(stats["guides"].get<double>(), 0.8 * static_cast<double>(stations)) << stats.dump();
  // No quad folded, and hardly a road crosses one it did not cross before.
  EXPECT_EQ(stats["foldovers"], 0) << stats.dump();
  EXPECT_LT(stats["crossings_added"].get<double>(), 0.005 * stats["road_edges"].get<double>()) << stats.dump();
  // The nearest warped road to a station's layout position is close for most stations. The
  // layout moves some stations kilometres from where the geography would put them (1 km rms
  // after the Helmert fit, for a mean edge of 770 m); there the guides stay short of their
  // targets rather than fold the map, so the tail is looser.
  const double edge = mean_edge(layout);
  const auto gaps = station_to_road(layout, roads);
  EXPECT_LT(quantile(gaps, 0.5), 0.02 * edge);
  EXPECT_LT(quantile(gaps, 0.75), 0.05 * edge);
  EXPECT_LT(stats["mean_guide_error"].get<double>(), 0.1 * edge) << stats.dump();
  EXPECT_GT(stats["helmert"]["rms"].get<double>(), 5 * stats["mean_guide_error"].get<double>()) << stats.dump();
  // The road data's credit comes with the roads.
  ASSERT_FALSE(roads["attribution"].empty());
  EXPECT_NE(roads["attribution"][0].get<std::string>().find("OpenStreetMap"), std::string::npos);

  // Cached: the same answer at once, and a 304 for its ETag.
  const auto again = live->get("/api/v1/cities/liechtenstein/layout/roads");
  EXPECT_EQ(again.header("x-result-cache"), "hit");
  EXPECT_EQ(again.body, r.body);
  EXPECT_EQ(live->get("/api/v1/cities/liechtenstein/layout/roads", {{"If-None-Match", r.header("etag")}}).status, 304);
}

TEST_F(SchematicRoads, TheLayoutParametersChangeTheRoads) {
  const auto layout = live->get_json("/api/v1/cities/liechtenstein/layout?lengths=uniform");
  const auto roads = live->get_json("/api/v1/cities/liechtenstein/layout/roads?lengths=uniform");
  EXPECT_EQ(roads["params"]["lengths"], "uniform");
  EXPECT_LT(roads["stats"]["mean_guide_error"].get<double>(), 0.1 * mean_edge(layout)) << roads["stats"].dump();
  EXPECT_LT(quantile(station_to_road(layout, roads), 0.5), 0.02 * mean_edge(layout));
}

TEST_F(SchematicRoads, MonacoBusesOnMonacosRoads) {
  const auto layout = live->get_json("/api/v1/cities/monaco/layout");
  const auto r = live->get("/api/v1/cities/monaco/layout/roads");
  ASSERT_EQ(r.status, 200) << r.body;
  const auto roads = nlohmann::json::parse(r.body);
  EXPECT_EQ(roads["road_network"]["id"], "monaco");
  EXPECT_GT(roads["stats"]["guides"].get<int>(), 10);
  EXPECT_EQ(roads["stats"]["foldovers"], 0);
  EXPECT_LT(roads["stats"]["mean_guide_error"].get<double>(), 0.1 * mean_edge(layout)) << roads["stats"].dump();
  EXPECT_LT(quantile(station_to_road(layout, roads), 0.5), 0.02 * mean_edge(layout));
}

TEST_F(SchematicRoads, NoRoadsIsA404NamingTheCityAndBadParametersA400) {
  // Vienna: no road network holds its stations; the city tells clients so (no request to 404).
  EXPECT_TRUE(live->get_json("/api/v1/cities/vienna")["road_network"].is_null());
  EXPECT_EQ(live->get_json("/api/v1/cities/liechtenstein")["road_network"], "liechtenstein");
  auto r = live->get("/api/v1/cities/vienna/layout/roads");
  expect_error(r, 404, "id");
  EXPECT_NE(error_of(r)["message"].get<std::string>().find("vienna"), std::string::npos) << r.body;
  expect_error(live->get("/api/v1/cities/atlantis/layout/roads"), 404, "id");
  expect_error(live->get("/api/v1/cities/liechtenstein/layout/roads?lengths=zigzag"), 400, "lengths");
  expect_error(live->get("/api/v1/cities/liechtenstein/layout/roads?time_limit_s=soon"), 400, "time_limit_s");
  expect_error(live->get("/api/v1/cities/liechtenstein/layout/roads?l_const=0"), 400, "l_const");
  expect_error(live->get("/api/v1/cities/liechtenstein/layout/roads?roads=nowhere"), 404, "roads");
  expect_error(live->get("/api/v1/cities/liechtenstein/layout/roads?roads=Not%20a%20slug"), 404, "roads");
  // Another network named explicitly: Monaco's roads hold none of Liechtenstein's stations.
  r = live->get("/api/v1/cities/liechtenstein/layout/roads?roads=monaco");
  EXPECT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(nlohmann::json::parse(r.body)["stats"]["road_edges"], 0);
}

}  // namespace
}  // namespace tourmap::test
