#include "api/routes.hpp"
#include "store/importer.hpp"
#include "store/migrate.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

namespace tourmap::api {
namespace {

// Handlers called through the router, without a socket.
class HandlersTest : public ::testing::Test {
 protected:
  HandlersTest() : pool(dir.file("t.db")), catalog(pool), deform(catalog), metro(catalog), ctx{pool, catalog, deform, metro, "test"} {
    auto db = pool.acquire();
    store::migrate(*db);
    store::import_metro(*db, {{"vienna", "Vienna", "Wiener Linien"}, store::MetroFormat::loom,
                              {test::data_file("metro/loom_wien.json")}, false});
    store::import_pois(*db, {"vienna", test::data_file("poi/vienna_sights_SEHENSWUERDIGOGD.json"), "sight", "Stadt Wien", false});
    add_api_routes(router, ctx);
  }

  Response call(const std::string& method, const std::string& path, std::map<std::string, std::string> query = {},
                const std::string& body = "") {
    Request req;
    req.method = method;
    req.path = path;
    req.query = std::move(query);
    req.body = body;
    req.content_type = "application/json";
    auto m = router.match(req);
    if (!m.route) return error_response(404, "not_found", "no route");
    try {
      return m.route->handler(req);
    } catch (const ApiError& e) {
      return error_response(e);
    }
  }

  test::TempDir dir;
  store::DbPool pool;
  Catalog catalog;
  DeformService deform;
  MetroService metro;
  AppContext ctx;
  Router router;
};

TEST_F(HandlersTest, CitiesAndMetro) {
  auto list = nlohmann::json::parse(call("GET", "/api/v1/cities").body);
  ASSERT_EQ(list["cities"].size(), 1u);
  EXPECT_EQ(list["cities"][0]["counts"]["stations"], 98);
  EXPECT_EQ(list["cities"][0]["attribution"][1], "Stadt Wien");

  auto metro = call("GET", "/api/v1/cities/vienna/metro");
  EXPECT_EQ(metro.content_type, "application/geo+json");
  auto fc = nlohmann::json::parse(metro.body);
  std::size_t stations = 0, edges = 0;
  for (const auto& f : fc["features"]) {
    if (f["properties"]["kind"] == "station") ++stations;
    if (f["properties"]["kind"] == "edge") ++edges;
  }
  EXPECT_EQ(stations, 98u);
  EXPECT_EQ(edges, 105u);
  EXPECT_EQ(fc["lines"].size(), 5u);
}

TEST_F(HandlersTest, PoisByBBoxAndPolygon) {
  auto all = nlohmann::json::parse(call("GET", "/api/v1/cities/vienna/pois").body);
  EXPECT_EQ(all["matched"], 63);
  // The inner city (Ring) only.
  auto inner = nlohmann::json::parse(
      call("GET", "/api/v1/cities/vienna/pois", {{"bbox", "16.355,48.198,16.385,48.218"}}).body);
  EXPECT_GT(inner["matched"].get<int>(), 0);
  EXPECT_LT(inner["matched"].get<int>(), 63);
  auto page = nlohmann::json::parse(call("GET", "/api/v1/cities/vienna/pois", {{"limit", "5"}, {"offset", "60"}}).body);
  EXPECT_EQ(page["returned"], 3);

  std::string body = R"({"within":{"type":"Polygon","coordinates":[[[16.355,48.198],[16.385,48.198],[16.385,48.218],[16.355,48.218],[16.355,48.198]]]}})";
  auto within = nlohmann::json::parse(call("POST", "/api/v1/cities/vienna/pois/query", {}, body).body);
  EXPECT_EQ(within["matched"], inner["matched"]);
}

TEST_F(HandlersTest, BadInputIs4xxNamingTheField) {
  auto expect = [&](const Response& r, int status, const std::string& field) {
    EXPECT_EQ(r.status, status) << r.body;
    auto err = nlohmann::json::parse(r.body)["error"];
    EXPECT_EQ(err["field"], field) << r.body;
  };
  expect(call("GET", "/api/v1/cities/atlantis"), 404, "id");
  expect(call("GET", "/api/v1/cities/vienna/pois", {{"bbox", "1,2,nan,4"}}), 400, "bbox");
  expect(call("GET", "/api/v1/cities/vienna/pois", {{"limit", "0"}}), 400, "limit");
  expect(call("POST", "/api/v1/cities/vienna/pois/query", {}, "[1,2"), 400, "body");
  expect(call("POST", "/api/v1/cities/vienna/pois/query", {}, R"({"limit":"ten"})"), 400, "limit");
  expect(call("POST", "/api/v1/cities/vienna/pois/query", {}, R"({"categories":"sight"})"), 400, "categories");
  expect(call("POST", "/api/v1/cities/vienna/pois/query", {}, R"({"colour":"red"})"), 400, "colour");
  expect(call("POST", "/api/v1/cities/vienna/pois/query", {}, R"({"within":{"type":"Polygon","coordinates":[]}})"),
         400, "within.coordinates");
  expect(call("GET", "/api/v1/roads/nope"), 404, "id");
}

TEST_F(HandlersTest, CatalogReloadsAfterImport) {
  auto before = catalog.city("vienna");
  {
    auto db = pool.acquire();
    auto csv = dir.write("museums.csv", "name,lon,lat\nAlbertina,16.3681,48.2046\nBelvedere,16.3809,48.1915\n");
    store::import_pois(*db, {"vienna", csv, "museum", "", false});
  }
  auto after = catalog.city("vienna");
  EXPECT_NE(before.get(), after.get());
  EXPECT_EQ(after->pois.size(), 2u);
  EXPECT_EQ(catalog.city("vienna").get(), after.get());  // unchanged version: same copy
}

}  // namespace
}  // namespace tourmap::api
