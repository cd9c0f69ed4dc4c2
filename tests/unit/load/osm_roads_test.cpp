#include "load/load_error.hpp"
#include "load/osm_roads.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace tourmap::load {
namespace {

using test::data_file;

TEST(OsmRoads, WestOaklandBz2) {
  OsmRoadStats stats;
  auto net = load_osm_roads(data_file("roads/West-Oakland.osm.bz2"), &stats);
  EXPECT_EQ(stats.osm_ways, 66u);
  EXPECT_EQ(net.ways.size(), 31u);    // every highway way is a road here
  EXPECT_EQ(net.edges.size(), 225u);  // PROVENANCE: 225 segments
  EXPECT_EQ(net.nodes.size(), 213u);  // PROVENANCE: 213 highway nodes
  for (const auto& e : net.edges) {
    ASSERT_LT(e.from, net.nodes.size());
    ASSERT_LT(e.to, net.nodes.size());
    EXPECT_NE(e.from, e.to);
  }
}

TEST(OsmRoads, LiechtensteinPbf) {
  auto net = load_osm_roads(data_file("roads/liechtenstein-latest.osm.pbf"));
  // PROVENANCE counts 56,015 segments over all highway=* ways; tourmap leaves out
  // proposed/construction/platform ways and areas.
  EXPECT_GT(net.edges.size(), 55000u);
  EXPECT_LE(net.edges.size(), 56015u);
  auto box = model::bbox_of(net);
  EXPECT_GT(box.min_lon, 9.39);
  EXPECT_LT(box.max_lon, 9.68);
}

TEST(OsmRoads, RoadClassFilter) {
  EXPECT_TRUE(is_road_class("residential"));
  EXPECT_TRUE(is_road_class("footway"));
  EXPECT_FALSE(is_road_class("proposed"));
  EXPECT_FALSE(is_road_class("construction"));
  EXPECT_FALSE(is_road_class(""));
}

TEST(OsmRoads, TruncatedFileIsALoadError) {
  std::ifstream in(data_file("roads/krems.osm.gz"), std::ios::binary);
  std::stringstream buf;
  buf << in.rdbuf();
  std::string bytes = buf.str();
  test::TempDir dir;
  auto path = dir.write("cut.osm.gz", bytes.substr(0, bytes.size() / 2));
  try {
    load_osm_roads(path);
    FAIL() << "expected LoadError";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read OSM data"), std::string::npos) << e.what();
  }
}

TEST(OsmRoads, MissingFileAndNoRoads) {
  EXPECT_THROW(load_osm_roads("/nonexistent.osm"), LoadError);
  test::TempDir dir;
  auto path = dir.write("empty.osm", R"(<?xml version='1.0'?><osm version="0.6"><node id="1" lat="1" lon="2"/></osm>)");
  EXPECT_THROW(load_osm_roads(path), LoadError);
}

TEST(OsmRoads, WaysAreSplitAtMissingNodes) {
  test::TempDir dir;
  auto path = dir.write("gap.osm", R"(<?xml version='1.0'?><osm version="0.6">
    <node id="1" lat="0" lon="0"/><node id="2" lat="0" lon="0.001"/>
    <node id="4" lat="0" lon="0.003"/><node id="5" lat="0" lon="0.004"/>
    <way id="10"><nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="4"/><nd ref="5"/><tag k="highway" v="residential"/></way>
    <way id="11"><nd ref="1"/><nd ref="5"/><tag k="highway" v="proposed"/></way>
  </osm>)");
  OsmRoadStats stats;
  auto net = load_osm_roads(path, &stats);
  ASSERT_EQ(net.ways.size(), 2u);  // 1-2 and 4-5
  EXPECT_EQ(net.edges.size(), 2u);
  EXPECT_EQ(stats.missing_nodes, 1u);
  EXPECT_EQ(stats.skipped_ways, 1u);
  EXPECT_EQ(net.ways[0].osm_id, 10);
  EXPECT_EQ(net.ways[1].osm_id, 10);
}

// Found by fuzz_osm_pbf: after some 20 000 runs the harness could no longer write its input
// file (EMFILE). libosmium reads a .pbf through a descriptor of its own and closes it only
// after a successful read, so every PBF that failed to parse leaked one; PBFs are now read
// from memory. Any truncated PBF shows it (tests/fuzz/corpus/osm_pbf/regression-fd-leak is
// the fuzz seed cut short). Compressed XML is checked the same way.
TEST(OsmRoads, FailedLoadsLeaveNoFileDescriptorOpen) {
  auto open_fds = [] {
    return std::distance(std::filesystem::directory_iterator("/proc/self/fd"), std::filesystem::directory_iterator());
  };
  test::TempDir dir;
  for (const std::string name : {"liechtenstein-latest.osm.pbf", "monaco.osm.gz", "West-Oakland.osm.bz2"}) {
    SCOPED_TRACE(name);
    std::ifstream in(data_file("roads/" + name), std::ios::binary);
    std::stringstream whole;
    whole << in.rdbuf();
    const auto cut = dir.write("cut-" + name, whole.str().substr(0, 200));
    const auto good = dir.write("good-" + name, whole.str());
    const auto before = open_fds();
    for (int i = 0; i < 20; ++i) EXPECT_THROW(load_osm_roads(cut), LoadError);
    EXPECT_EQ(open_fds(), before);
    EXPECT_GT(load_osm_roads(good).ways.size(), 10u);  // and a whole file still loads
    EXPECT_EQ(open_fds(), before);
  }
}

}  // namespace
}  // namespace tourmap::load
