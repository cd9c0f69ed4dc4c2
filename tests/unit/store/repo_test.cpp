#include "store/importer.hpp"
#include "store/manifest.hpp"
#include "store/migrate.hpp"
#include "store/repo.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include "load/load_error.hpp"

#include <gtest/gtest.h>

namespace tourmap::store {
namespace {

using test::data_file;

class RepoTest : public ::testing::Test {
 protected:
  RepoTest() : db(dir.file("t.db")) { migrate(db); }

  std::int64_t count(const std::string& table) {
    auto st = db.prepare("SELECT COUNT(*) FROM " + table);
    st.step();
    return st.int64(0);
  }

  test::TempDir dir;
  Db db;
};

model::MetroNetwork tiny_network() {
  model::MetroNetwork net;
  net.lines = {{"l1", "Red", "ff0000"}};
  net.nodes = {{"a", "A", "Alpha", {16.0, 48.0}}, {"j", "", "", {16.05, 48.0}}, {"b", "B", "Beta", {16.1, 48.1}}};
  net.edges = {{0, 1, {0}, {{16.0, 48.0}, {16.05, 48.0}}}, {1, 2, {0}, {{16.05, 48.0}, {16.08, 48.05}, {16.1, 48.1}}}};
  return net;
}

TEST_F(RepoTest, CityRoundTrip) {
  auto v1 = save_city_metro(db, {"tiny", "Tiny Town", "test data"}, tiny_network(), {"", "", "tiny.json", "f1", 7, 0.1});
  model::Poi poi;
  poi.id = "p1";
  poi.name = "Museum";
  poi.pos = {16.02, 48.01};
  poi.rank = 2.0;
  poi.image_url = "http://img";
  auto v2 = save_city_pois(db, "tiny", "poi data", {poi}, {"", "", "pois.csv", "f2", 1, 0.1});
  EXPECT_GT(v2, v1);

  auto city = load_city(db, "tiny");
  ASSERT_TRUE(city);
  EXPECT_EQ(city->info.name, "Tiny Town");
  EXPECT_EQ(city->info.version, v2);
  EXPECT_EQ(city->info.station_count, 2u);
  EXPECT_EQ(city->info.poi_count, 1u);
  EXPECT_EQ(city->info.attribution, "test data");
  EXPECT_EQ(city->info.poi_attribution, "poi data");
  EXPECT_NEAR(city->info.projection.origin.lon, 16.05, 1e-12);
  ASSERT_EQ(city->metro.edges.size(), 2u);
  EXPECT_EQ(city->metro.edges[1].geometry.size(), 3u);
  EXPECT_EQ(city->metro.edges[1].geometry[1].lat, 48.05);
  EXPECT_FALSE(city->metro.nodes[1].is_station());
  ASSERT_EQ(city->pois.size(), 1u);
  EXPECT_EQ(city->pois[0].rank, 2.0);
  EXPECT_FALSE(city->pois[0].popularity.has_value());

  // Re-importing the metro keeps the POIs.
  save_city_metro(db, {"tiny", "Tiny Town", "test data"}, tiny_network(), {"", "", "tiny.json", "f3", 7, 0.1});
  EXPECT_EQ(load_city(db, "tiny")->pois.size(), 1u);
  EXPECT_TRUE(delete_city(db, "tiny"));
  EXPECT_EQ(count("pois"), 0);  // cascades
  EXPECT_EQ(count("metro_nodes"), 0);
  EXPECT_FALSE(delete_city(db, "tiny"));
}

TEST_F(RepoTest, FailedWriteChangesNothing) {
  save_city_metro(db, {"tiny", "Tiny Town", ""}, tiny_network(), {"", "", "tiny.json", "f1", 7, 0.1});
  auto before_nodes = count("metro_nodes");
  auto before_imports = count("imports");
  // Make the third node insert fail half-way through a re-import.
  db.exec("CREATE TEMP TRIGGER boom BEFORE INSERT ON metro_nodes WHEN NEW.id = 'b' "
          "BEGIN SELECT RAISE(ABORT, 'injected failure'); END");
  auto net = tiny_network();
  net.nodes[0].name = "Changed";
  EXPECT_THROW(save_city_metro(db, {"tiny", "Renamed", ""}, net, {"", "", "tiny.json", "f2", 7, 0.1}), DbError);
  db.exec("DROP TRIGGER boom");
  EXPECT_EQ(count("metro_nodes"), before_nodes);
  EXPECT_EQ(count("imports"), before_imports);
  auto city = load_city(db, "tiny");
  EXPECT_EQ(city->info.name, "Tiny Town");
  EXPECT_EQ(city->metro.nodes[0].name, "Alpha");
}

TEST_F(RepoTest, PoisNeedAnExistingCity) {
  EXPECT_THROW(save_city_pois(db, "nowhere", "", {}, {}), DbError);
  EXPECT_EQ(count("imports"), 0);
}

TEST_F(RepoTest, RoadNetworkRoundTripRebuildsWays) {
  model::RoadNetwork net;
  net.nodes = {{1, {7.0, 43.0}}, {2, {7.001, 43.0}}, {3, {7.002, 43.001}}, {4, {7.0, 43.002}}};
  net.ways = {{100, "residential", "Rue A", {0, 1, 2}}, {101, "footway", "", {2, 3}}};
  net.edges = model::edges_of(net.ways);
  auto version = save_road_network(db, {"mini", "Mini", "osm"}, net, {"", "", "mini.osm", "f", 9, 0.1});
  auto info = find_road_network(db, "mini");
  ASSERT_TRUE(info);
  EXPECT_EQ(info->version, version);
  EXPECT_EQ(info->edge_count, 3u);
  auto loaded = load_road_network(db, "mini");
  ASSERT_TRUE(loaded);
  ASSERT_EQ(loaded->ways.size(), 2u);
  EXPECT_EQ(loaded->ways[0].nodes, (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(loaded->ways[1].highway, "footway");
  EXPECT_EQ(loaded->nodes[3].osm_id, 4);
  EXPECT_EQ(loaded->edges.size(), 3u);
  EXPECT_EQ(list_road_networks(db).size(), 1u);
  EXPECT_TRUE(delete_road_network(db, "mini"));
  EXPECT_EQ(count("road_edges"), 0);
}

// The context layers go in with the roads and come back as they went in; a failed write leaves
// the earlier ones; deleting the network deletes them.
TEST_F(RepoTest, RoadContextRoundTripWithTheRoads) {
  model::RoadNetwork net;
  net.nodes = {{1, {7.0, 43.0}}, {2, {7.001, 43.0}}};
  net.ways = {{100, "residential", "Rue A", {0, 1}}};
  net.edges = model::edges_of(net.ways);
  model::ContextLayers layers;
  layers.areas.push_back({model::ContextAreaKind::sea,
                          {{{7.0, 42.9}, {7.1, 42.9}, {7.1, 43.0}}, {{7.05, 42.95}, {7.06, 42.95}, {7.05, 42.96}}}});
  layers.areas.push_back({model::ContextAreaKind::park, {{{7.0, 43.0}, {7.0001, 43.0}, {7.0, 43.0001}}}});
  layers.lines.push_back({model::ContextLineKind::river, "Rhein", false, {{9.5, 47.1}, {9.51, 47.2}}});
  layers.lines.push_back({model::ContextLineKind::railway, "", true, {{9.5, 47.1}, {9.52, 47.1}, {9.53, 47.1}}});
  layers.places.push_back({model::ContextPlaceKind::town, "Vaduz", {9.52, 47.14}, 14});
  save_road_network(db, {"mini", "Mini", "osm"}, net, {"", "", "mini.osm", "f", 9, 0.1}, layers);
  const auto back = load_road_context(db, "mini");
  ASSERT_EQ(back.areas.size(), 2u);
  EXPECT_EQ(back.areas[0].kind, model::ContextAreaKind::sea);
  ASSERT_EQ(back.areas[0].rings.size(), 2u);
  EXPECT_EQ(back.areas[0].rings[1][1].lon, 7.06);
  EXPECT_EQ(back.areas[0].rings[1][2].lat, 42.96);
  EXPECT_EQ(back.areas[1].kind, model::ContextAreaKind::park);
  ASSERT_EQ(back.lines.size(), 2u);
  EXPECT_EQ(back.lines[0].name, "Rhein");
  EXPECT_FALSE(back.lines[0].tunnel);
  EXPECT_TRUE(back.lines[1].tunnel);
  EXPECT_EQ(back.lines[1].kind, model::ContextLineKind::railway);
  EXPECT_EQ(back.lines[1].points.size(), 3u);
  ASSERT_EQ(back.places.size(), 1u);
  EXPECT_EQ(back.places[0].name, "Vaduz");
  EXPECT_EQ(back.places[0].rank, 14);
  EXPECT_EQ(back.places[0].pos.lon, 9.52);

  // A failing write of the network (a trigger) keeps the context it had.
  db.exec("CREATE TRIGGER boom BEFORE INSERT ON road_context WHEN NEW.kind = 'forest' BEGIN SELECT RAISE(ABORT, 'boom'); END");
  model::ContextLayers other;
  other.areas.push_back({model::ContextAreaKind::forest, {{{7.0, 43.0}, {7.1, 43.0}, {7.0, 43.1}}}});
  EXPECT_THROW(save_road_network(db, {"mini", "Mini", "osm"}, net, {"", "", "mini.osm", "g", 9, 0.1}, other), DbError);
  db.exec("DROP TRIGGER boom");
  EXPECT_EQ(load_road_context(db, "mini").areas.size(), 2u);

  EXPECT_TRUE(delete_road_network(db, "mini"));
  EXPECT_EQ(count("road_context"), 0);
  EXPECT_TRUE(load_road_context(db, "mini").areas.empty());
}

TEST_F(RepoTest, ResultCache) {
  EXPECT_FALSE(cache_get(db, "k"));
  cache_put(db, "k", "layout", {"application/json", std::string("{\"a\":1}\0x", 9)});
  auto hit = cache_get(db, "k");
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->body.size(), 9u);  // binary-safe
  EXPECT_EQ(cache_purge(db, "other"), 0u);
  EXPECT_EQ(cache_purge(db, "layout"), 1u);
  EXPECT_FALSE(cache_get(db, "k"));
}

TEST_F(RepoTest, ImportSkipsUnchangedFilesUnlessForced) {
  MetroImport req{{"freiburg", "Freiburg", ""}, MetroFormat::loom, {data_file("metro/loom_freiburg.json")}, false};
  auto first = import_metro(db, req);
  EXPECT_FALSE(first.skipped);
  EXPECT_EQ(first.rows, 76u + 79u + 5u);
  auto second = import_metro(db, req);
  EXPECT_TRUE(second.skipped);
  EXPECT_EQ(second.version, first.version);
  req.force = true;
  auto third = import_metro(db, req);
  EXPECT_FALSE(third.skipped);
  EXPECT_GT(third.version, first.version);
}

TEST_F(RepoTest, BadFileImportChangesNothing) {
  import_metro(db, {{"freiburg", "Freiburg", ""}, MetroFormat::loom, {data_file("metro/loom_freiburg.json")}, false});
  auto imports = count("imports");
  auto csv = dir.write("bad.csv", "line_id,seq_on_line,name,lat\nA,1,X,38.7\n");
  EXPECT_THROW(import_metro(db, {{"freiburg", "Freiburg", ""}, MetroFormat::line_csv, {csv}, true}), load::LoadError);
  EXPECT_EQ(count("imports"), imports);
  EXPECT_EQ(load_city(db, "freiburg")->metro.nodes.size(), 76u);
}

TEST_F(RepoTest, PoisFarOutsideTheCityFailTheImport) {
  import_metro(db, {{"freiburg", "Freiburg", ""}, MetroFormat::loom, {data_file("metro/loom_freiburg.json")}, false});
  auto imports = count("imports");
  // Berlin's museums are 600 km from Freiburg's trams.
  try {
    import_pois(db, {"freiburg", data_file("poi/berlin_museums_osm_r360.js"), "museum", "", false});
    ADD_FAILURE() << "imported";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("POI 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("outside freiburg"), std::string::npos) << e.what();
  }
  // Longitude and latitude swapped in the second record: named, nothing imported.
  auto swapped = dir.write("swapped.csv", "name,lon,lat\nMuenster,7.8529,47.9956\nSchlossberg,47.9950,7.8600\n");
  try {
    import_pois(db, {"freiburg", swapped, "sight", "", false});
    ADD_FAILURE() << "imported";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("POI 1 ('Schlossberg'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("swapped"), std::string::npos) << e.what();
  }
  EXPECT_EQ(count("imports"), imports);
  EXPECT_TRUE(load_city(db, "freiburg")->pois.empty());
  // A POI just beyond the network (the limit is at least 50 km) is fine.
  auto near = dir.write("near.csv", "name,lon,lat\nMuenster,7.8529,47.9956\nTiti,8.1500,47.9000\n");
  EXPECT_EQ(import_pois(db, {"freiburg", near, "sight", "", false}).rows, 2u);
}

TEST_F(RepoTest, ImportValidatesIds) {
  EXPECT_THROW(import_metro(db, {{"Bad Id", "X", ""}, MetroFormat::loom, {data_file("metro/loom_freiburg.json")}, false}),
               std::invalid_argument);
  EXPECT_THROW(import_pois(db, {"ghost", data_file("poi/berlin_museums_osm_r360.js"), "", "", false}),
               std::invalid_argument);
  EXPECT_TRUE(is_valid_id("north-bayreuth"));
  EXPECT_FALSE(is_valid_id("-x"));
  EXPECT_FALSE(is_valid_id("../x"));
}

TEST(Manifest, ParsesAndResolvesPaths) {
  auto m = parse_manifest(R"({"cities":[{"id":"v","name":"V","metro":{"format":"loom","files":["metro/a.json"]},
                               "pois":{"file":"/abs/p.csv","category":"sight"}}],
                              "roads":[{"id":"r","name":"R","file":"roads/r.osm"}]})",
                          "/data");
  ASSERT_EQ(m.metros.size(), 1u);
  EXPECT_EQ(m.metros[0].files[0], "/data/metro/a.json");
  ASSERT_EQ(m.pois.size(), 1u);
  EXPECT_EQ(m.pois[0].file, "/abs/p.csv");
  EXPECT_EQ(m.pois[0].default_category, "sight");
  EXPECT_EQ(m.roads[0].file, "/data/roads/r.osm");
  EXPECT_THROW(parse_manifest("{", "/d"), std::invalid_argument);
  EXPECT_THROW(parse_manifest(R"({"cities":[{"id":"v","name":"V"}]})", "/d"), std::invalid_argument);
  EXPECT_THROW(parse_manifest(R"({"cities":[{"id":"v","name":"V","metro":{"format":"kml","files":[]}}]})", "/d"),
               std::invalid_argument);
}

// Found by fuzz_manifest (its input first): a number beyond double's range made the parser
// throw nlohmann's out_of_range, not the documented std::invalid_argument.
TEST(Manifest, NumberTooLargeForADoubleIsInvalidArgument) {
  EXPECT_THROW(parse_manifest("-922337429496721.7976931348623157e309962036854775808", "/d"), std::invalid_argument);
  EXPECT_THROW(parse_manifest(R"({"cities":[],"roads":[{"id":"r","name":1e999}]})", "/d"), std::invalid_argument);
}

}  // namespace
}  // namespace tourmap::store
