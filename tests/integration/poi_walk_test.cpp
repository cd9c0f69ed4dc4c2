// GET /api/v1/cities/{id}/pois/{poi}/walk against a real server (issue 17, part 4):
// Liechtenstein imported whole from its extract (transit, POIs, roads); every POI gets its
// nearest stations by walking over the roads, never shorter than the straight line, the path
// running from the POI to the station along the distance it reports, and warped into the
// default layout with the transform the layout gives its POIs. Bad parameters are 400s naming
// the field; a city without roads (Vienna, from LOOM) a 409 naming `road_network`.

#include "live_server_suite.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <string>

namespace tourmap::test {
namespace {

class PoiWalk : public LiveServerSuite<PoiWalk> {
 protected:
  static void SetUpTestSuite() {
    LiveServerSuite::SetUpTestSuite();
    const auto key = create_key(*live);
    const auto r = http_request(live->port(), "PUT", "/api/v1/cities/liechtenstein/source?name=Liechtenstein&modes=train,bus",
                                bearer(key), file_bytes(data_file("roads/liechtenstein-latest.osm.pbf")));
    ASSERT_EQ(r.status, 200) << r.body;
  }
};

struct LonLat {
  double lon, lat;
};

LonLat lonlat(const nlohmann::json& pair) { return {pair[0].get<double>(), pair[1].get<double>()}; }

// Haversine on the mean sphere: within 0.5% of the server's WGS84 geodesics at this latitude.
double metres(LonLat a, LonLat b) {
  constexpr double kR = 6371008.8, kRad = std::numbers::pi / 180;
  const double dlat = (b.lat - a.lat) * kRad, dlon = (b.lon - a.lon) * kRad;
  const double h = std::sin(dlat / 2) * std::sin(dlat / 2) +
                   std::cos(a.lat * kRad) * std::cos(b.lat * kRad) * std::sin(dlon / 2) * std::sin(dlon / 2);
  return 2 * kR * std::asin(std::sqrt(h));
}

double planar(const nlohmann::json& a, const nlohmann::json& b) {
  return std::hypot(a[0].get<double>() - b[0].get<double>(), a[1].get<double>() - b[1].get<double>());
}

// Feature id -> feature of a FeatureCollection.
std::map<std::string, nlohmann::json> by_id(const nlohmann::json& features) {
  std::map<std::string, nlohmann::json> out;
  for (const auto& f : features) out[f["id"].get<std::string>()] = f;
  return out;
}

TEST_F(PoiWalk, EveryLiechtensteinPoiWalksAlongTheRoadsToItsNearestStations) {
  EXPECT_EQ(live->get_json("/api/v1/cities/liechtenstein")["road_network"], "liechtenstein");
  const auto pois = live->get_json("/api/v1/cities/liechtenstein/pois")["features"];
  ASSERT_EQ(pois.size(), 26u);
  const auto stations = by_id(live->get_json("/api/v1/cities/liechtenstein/metro")["features"]);
  const auto layout = live->get_json("/api/v1/cities/liechtenstein/layout");
  const auto layout_pois = by_id(layout["pois"]["features"]);
  const auto layout_stations = by_id(layout["stations"]["features"]);

  std::size_t with_walks = 0, walks_seen = 0;
  for (const auto& poi : pois) {
    const std::string id = poi["id"];
    const auto body = live->get_json("/api/v1/cities/liechtenstein/pois/" + id + "/walk");
    SCOPED_TRACE(id + " " + body.dump().substr(0, 400));
    EXPECT_EQ(body["city"], "liechtenstein");
    EXPECT_EQ(body["road_network"]["id"], "liechtenstein");
    EXPECT_EQ(body["poi"]["id"], id);
    EXPECT_EQ(body["poi"]["name"], poi["properties"]["name"]);
    const LonLat at = lonlat(poi["geometry"]["coordinates"]);
    EXPECT_EQ(body["poi"]["lon"].get<double>(), at.lon);
    EXPECT_EQ(body["poi"]["lat"].get<double>(), at.lat);
    EXPECT_FALSE(body["attribution"].empty());
    // The same warp as the layout's POIs: the POI lands where GET /layout draws it (rounded to
    // 0.1 there, to 0.001 here).
    const auto& drawn = layout_pois.at(id)["geometry"]["coordinates"];
    for (int i : {0, 1}) EXPECT_NEAR(body["poi"]["layout"][i].get<double>(), drawn[i].get<double>(), 0.0515);

    const auto& walks = body["walks"];
    EXPECT_LE(walks.size(), 3u);
    with_walks += !walks.empty();
    double previous = 0;
    for (const auto& w : walks) {
      ++walks_seen;
      const std::string sid = w["station"]["id"];
      ASSERT_TRUE(stations.count(sid)) << sid;
      EXPECT_EQ(w["station"]["name"], stations.at(sid)["properties"]["name"]);
      const LonLat station = lonlat(stations.at(sid)["geometry"]["coordinates"]);
      const double d = w["distance_m"], straight = w["straight_m"];
      EXPECT_GE(d, previous);  // nearest first
      previous = d;
      EXPECT_LE(d, 2000.0);
      EXPECT_GE(d, straight);
      EXPECT_NEAR(straight, metres(at, station), 0.005 * straight + 0.1);
      EXPECT_NEAR(w["minutes"].get<double>(), d / 80.0, 0.051);  // 4.8 km/h, to 0.1 min
      // The path runs from the POI to the station, as long as the distance it reports.
      const auto& path = w["path"];
      ASSERT_GE(path.size(), 2u);
      EXPECT_LE(metres(lonlat(path.front()), at), 0.2);
      EXPECT_LE(metres(lonlat(path.back()), station), 0.2);
      double along = 0;
      for (std::size_t i = 1; i < path.size(); ++i) along += metres(lonlat(path[i - 1]), lonlat(path[i]));
      EXPECT_NEAR(along, d, 0.005 * d + 0.2 * static_cast<double>(path.size()));
      // Warped point by point; its ends where the layout draws the POI and the station.
      const auto& path_layout = w["path_layout"];
      ASSERT_EQ(path_layout.size(), path.size());
      EXPECT_LE(planar(path_layout.front(), body["poi"]["layout"]), 0.01);
      // The warp interpolates the stations exactly (none of Liechtenstein's share a position,
      // which would move them apart in the layout's input): both ends rounded to 0.001.
      EXPECT_LE(planar(path_layout.back(), layout_stations.at(sid)["geometry"]["coordinates"]), 0.01);
    }
  }
  // Most of Liechtenstein's sights are in its towns along the bus lines.
  EXPECT_GE(with_walks, 20u);
  EXPECT_GE(walks_seen, 50u);
}

TEST_F(PoiWalk, VaduzMuseumAndParameters) {
  const std::string base = "/api/v1/cities/liechtenstein/pois/n315636837/walk";  // Landesmuseum, Vaduz
  const auto three = live->get_json(base);
  EXPECT_EQ(three["poi"]["name"], "Liechtensteinisches Landesmuseum Vaduz");
  ASSERT_EQ(three["walks"].size(), 3u);
  const double nearest = three["walks"][0]["distance_m"];

  const auto five = live->get_json(base + "?stations=5&max_m=5000");
  ASSERT_EQ(five["walks"].size(), 5u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(five["walks"][i]["station"], three["walks"][i]["station"]);
  EXPECT_EQ(five["params"]["stations"], 5);
  EXPECT_EQ(five["params"]["max_m"], 5000);

  const auto one = live->get_json(base + "?stations=1");
  ASSERT_EQ(one["walks"].size(), 1u);
  EXPECT_EQ(one["walks"][0]["station"], three["walks"][0]["station"]);

  // A cap just under the nearest walk (Vaduz Post, ~177 m) leaves nothing; just over it, the
  // nearest alone fits (the second, Städtle, is ~412 m).
  const double second = three["walks"][1]["distance_m"];
  ASSERT_GT(nearest, 101.0);
  ASSERT_GT(second, nearest + 2);
  EXPECT_TRUE(live->get_json(base + "?max_m=" + std::to_string(nearest - 1))["walks"].empty());
  const auto capped = live->get_json(base + "?max_m=" + std::to_string(nearest + 1));
  ASSERT_EQ(capped["walks"].size(), 1u);
  EXPECT_EQ(capped["walks"][0]["station"], three["walks"][0]["station"]);
}

TEST_F(PoiWalk, BadParametersNameTheField) {
  const std::string base = "/api/v1/cities/liechtenstein/pois/n315636837/walk";
  for (const char* q : {"?stations=0", "?stations=6", "?stations=two", "?stations=2.5"})
    expect_error(live->get(base + q), 400, "stations");
  for (const char* q : {"?max_m=99", "?max_m=5001", "?max_m=nan", "?max_m=", "?max_m=1e9"})
    expect_error(live->get(base + q), 400, "max_m");
  expect_error(live->get("/api/v1/cities/liechtenstein/pois/n0/walk"), 404, "poi");
  expect_error(live->get("/api/v1/cities/nowhere/pois/n315636837/walk"), 404, "id");
}

TEST_F(PoiWalk, CityWithoutRoadsSaysSo) {
  EXPECT_TRUE(live->get_json("/api/v1/cities/vienna")["road_network"].is_null());
  const auto pois = live->get_json("/api/v1/cities/vienna/pois?limit=1")["features"];
  ASSERT_EQ(pois.size(), 1u);
  const auto r = live->get("/api/v1/cities/vienna/pois/" + pois[0]["id"].get<std::string>() + "/walk");
  expect_error(r, 409, "road_network");
  EXPECT_NE(error_of(r)["message"].get<std::string>().find("road network"), std::string::npos) << r.body;
  // An unknown POI of that city is still a 404 naming the POI.
  expect_error(live->get("/api/v1/cities/vienna/pois/nope/walk"), 404, "poi");
}

}  // namespace
}  // namespace tourmap::test
