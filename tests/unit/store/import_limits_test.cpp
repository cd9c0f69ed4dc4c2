// The importer with import limits and stop tokens (a refused or stopped import changes
// nothing), and re-imports after a delete (the same bytes import again).

#include "store/importer.hpp"
#include "store/manifest.hpp"
#include "store/migrate.hpp"
#include "store/repo.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include "load/load_error.hpp"
#include "util/stop.hpp"

#include <gtest/gtest.h>

namespace tourmap::store {
namespace {

using test::data_file;

class ImportTest : public ::testing::Test {
 protected:
  ImportTest() : db(dir.file("t.db")) { migrate(db); }

  std::int64_t count(const std::string& table) {
    auto st = db.prepare("SELECT COUNT(*) FROM " + table);
    st.step();
    return st.int64(0);
  }

  MetroImport freiburg() {
    return {{"freiburg", "Freiburg", ""}, MetroFormat::loom, {data_file("metro/loom_freiburg.json")}, false};
  }

  test::TempDir dir;
  Db db;
};

TEST_F(ImportTest, DeletedCityImportsAgainFromTheSameFiles) {
  auto first = import_metro(db, freiburg());
  ASSERT_FALSE(first.skipped);
  EXPECT_TRUE(import_metro(db, freiburg()).skipped);  // unchanged: still a no-op
  ASSERT_TRUE(delete_city(db, "freiburg"));
  auto again = import_metro(db, freiburg());
  EXPECT_FALSE(again.skipped);
  EXPECT_GT(again.version, first.version);
  ASSERT_TRUE(find_city(db, "freiburg"));
  EXPECT_EQ(load_city(db, "freiburg")->metro.nodes.size(), 76u);
  EXPECT_TRUE(import_metro(db, freiburg()).skipped);  // and unchanged again afterwards
}

TEST_F(ImportTest, PoisOfADeletedAndRecreatedCityImportAgain) {
  MetroImport vienna{{"vienna", "Vienna", ""}, MetroFormat::loom, {data_file("metro/loom_wien.json")}, false};
  PoiImport sights{"vienna", data_file("poi/vienna_sights_SEHENSWUERDIGOGD.json"), "sight", "", false};
  import_metro(db, vienna);
  EXPECT_FALSE(import_pois(db, sights).skipped);
  EXPECT_TRUE(import_pois(db, sights).skipped);
  ASSERT_TRUE(delete_city(db, "vienna"));
  EXPECT_FALSE(import_metro(db, vienna).skipped);
  EXPECT_EQ(find_city(db, "vienna")->poi_count, 0u);  // the delete took them
  auto pois = import_pois(db, sights);
  EXPECT_FALSE(pois.skipped);
  EXPECT_EQ(pois.rows, 63u);
  EXPECT_EQ(find_city(db, "vienna")->poi_count, 63u);
  // A metro re-import keeps the POIs and does not make their file stale.
  import_metro(db, {vienna.city, vienna.format, vienna.files, true});
  EXPECT_TRUE(import_pois(db, sights).skipped);
}

TEST_F(ImportTest, DeletedRoadNetworkImportsAgainFromTheSameFile) {
  RoadImport oakland{{"west-oakland", "West Oakland", ""}, data_file("roads/West-Oakland.osm.bz2"), false};
  EXPECT_FALSE(import_roads(db, oakland).skipped);
  EXPECT_TRUE(import_roads(db, oakland).skipped);
  ASSERT_TRUE(delete_road_network(db, "west-oakland"));
  EXPECT_FALSE(delete_road_network(db, "west-oakland"));
  auto again = import_roads(db, oakland);
  EXPECT_FALSE(again.skipped);
  ASSERT_TRUE(find_road_network(db, "west-oakland"));
  EXPECT_EQ(find_road_network(db, "west-oakland")->edge_count, 225u);
  // Deleting one target leaves the others' imports current.
  import_metro(db, freiburg());
  ASSERT_TRUE(delete_road_network(db, "west-oakland"));
  EXPECT_TRUE(import_metro(db, freiburg()).skipped);
}

TEST_F(ImportTest, LimitExceededChangesNothing) {
  import_metro(db, freiburg());
  const auto imports = count("imports");
  load::ImportLimits limits;
  limits.max_metro_nodes = 10;
  auto request = freiburg();
  request.force = true;
  try {
    import_metro(db, request, limits);
    FAIL();
  } catch (const load::LimitExceeded& e) {
    EXPECT_EQ(e.limit(), "max_metro_nodes");
    EXPECT_EQ(e.value(), 10u);
  }
  limits = {};
  limits.max_pois = 10;
  EXPECT_THROW(import_pois(db, {"freiburg", data_file("poi/berlin_museums_osm_r360.js"), "museum", "", false}, limits),
               load::LimitExceeded);
  limits = {};
  limits.max_road_edges = 10;
  EXPECT_THROW(import_roads(db, {{"oakland", "Oakland", ""}, data_file("roads/West-Oakland.osm.bz2"), false}, limits),
               load::LimitExceeded);
  EXPECT_EQ(count("imports"), imports);
  EXPECT_EQ(load_city(db, "freiburg")->metro.nodes.size(), 76u);
  EXPECT_FALSE(find_road_network(db, "oakland"));
}

TEST_F(ImportTest, StoppedImportChangesNothing) {
  util::StopToken expired;
  expired.deadline = util::StopToken::Clock::now() - std::chrono::seconds(1);
  util::StopScope scope(expired);
  EXPECT_THROW(import_metro(db, freiburg()), util::Stopped);
  EXPECT_THROW(import_roads(db, {{"monaco", "Monaco", ""}, data_file("roads/monaco.osm.gz"), false}), util::Stopped);
  EXPECT_EQ(count("imports"), 0);
  EXPECT_EQ(count("cities"), 0);
  EXPECT_EQ(count("road_networks"), 0);
}

TEST_F(ImportTest, ManifestPassesTheLimits) {
  Manifest m;
  m.metros.push_back(freiburg());
  load::ImportLimits limits;
  limits.max_metro_edges = 5;
  EXPECT_THROW(run_manifest(db, m, false, nullptr, limits), load::LimitExceeded);
  EXPECT_EQ(run_manifest(db, m, false, nullptr).size(), 1u);
}

}  // namespace
}  // namespace tourmap::store
