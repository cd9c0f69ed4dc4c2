#include "load/load_error.hpp"
#include "load/osm_roads.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <fstream>
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

// Found by fuzz_osm_pbf (ASan heap-buffer-overflow; this is its input,
// tests/fuzz/corpus/osm_pbf/regression-tag-nul): the file's string table holds "\0es" (a NUL
// byte inside a string), which libosmium's PBF reader copies into way 108's tag list as it is.
// TagList::operator[] then walked that list out of step (key "es", value past the end) and
// read beyond its 64 KiB buffer. The loader now reads tags within the list's bounds.
TEST(OsmRoads, PbfTagWithANulByteIsReadWithinTheTagList) {
  const std::string pbf(
      "\x00\x00\x00\x0d\x0a\x09\x4f\x53\x4d\x48\x65\x61\x64\x65\x72\x18\x2d\x0a\x2b\x22\x0e\x4f\x73\x6d"
      "\x53\x63\x68\x65\x6d\x61\x2d\x56\x30\x2e\x36\x22\x0a\x44\x65\x6e\x73\x65\x4e\x6f\x64\x65\x73\x82"
      "\x01\x0c\x74\x6f\x75\x72\x6d\x61\x70\x2d\x73\x65\x65\x64\x00\x00\x00\x0c\x0a\x07\x4f\x53\x4d\x44"
      "\x61\x74\x61\x18\xdf\x02\x0a\xdc\x02\x0a\x86\x01\x0a\x00\x0a\x07\x68\x69\x67\x68\x77\x61\x79\x0a"
      "\x04\x6e\x61\x6d\x65\x0a\x07\x70\x72\x69\x6d\x61\x72\x79\x0a\x05\x53\x6f\x75\x74\x68\x0a\x0b\x72"
      "\x65\x73\x69\x64\x65\x6e\x74\x69\x61\x6c\x0a\x09\x73\x65\x63\x6f\x6e\x64\x61\x72\x79\x0a\x0a\x4e"
      "\x6f\x72\x74\x68\x20\x26\x20\x43\x6f\x0a\x08\x74\x65\x72\x74\x69\x61\x72\x79\x0a\x07\x66\x6f\x6f"
      "\x74\x77\x61\x79\x0a\x07\x73\x65\x72\x76\x69\x63\x65\x0a\x0c\x63\x6f\x6e\x73\x74\x72\x75\x63\x74"
      "\x69\x6f\x6e\x0a\x04\x61\x72\x65\x61\x0a\x0a\x70\x65\x64\x65\x73\x74\x72\x68\x61\x6e\x0a\x03\x00"
      "\x65\x73\x12\x4a\x12\x48\x0a\x09\x02\x02\x02\x02\x02\x02\x02\x02\x02\x42\x11\x80\xf2\xd5\xcb\x03"
      "\x00\x00\xa0\x8d\x06\x00\x00\xa0\x8d\x06\x00\x00\x4a\x1d\x80\xda\x82\x9c\x01\xa0\x8d\x06\xa0\x8d"
      "\x06\xbf\x9a\x0c\xa0\x8d\x06\xa0\x8d\x06\xbf\x9a\x0c\xa0\x8d\x06\xa0\x8d\x06\x52\x09\x00\x00\x00"
      "\x00\x00\x00\x0d\x00\x00\x12\x81\x01\x1a\x0f\x08\x65\x12\x02\x01\x02\x1a\x02\x03\x04\x42\x03\x02"
      "\x02\x02\xe9\x0d\x08\x66\x12\x01\x01\x1a\x01\x05\x42\x03\x08\x02\x02\x1a\x0f\x08\x67\x12\x02\x01"
      "\x02\x1a\x02\x06\x07\x42\x03\x0e\x02\x02\x1a\x0d\x08\x68\x12\x01\x01\x1a\x01\x08\x42\x03\x02\x06"
      "\x06\x1a\x0e\x08\x69\x12\x01\x01\x1a\x01\x09\x42\x04\x04\x06\x06\x00\x1a\x0e\x08\x6a\x12\x01\x01"
      "\x1a\x01\x0a\x42\x04\x06\x06\x06\x42\x1a\x0d\x08\x6b\x12\x01\x01\x1a\x01\x0b\x42\x03\x02\x08\x08"
      "\x1a\x10\x08\x6c\x12\x02\x01\x0c\x1a\x02\x0d\x0e\x42\x04\x08\x02\x05\x04\x88\x01\x64",
      429);
  test::TempDir dir;
  OsmRoadStats stats;
  const auto net = load_osm_roads(dir.write("nul.osm.pbf", pbf), &stats);
  EXPECT_EQ(stats.osm_nodes, 9u);
  EXPECT_EQ(stats.osm_ways, 7u);
  ASSERT_EQ(net.ways.size(), 6u);
  const auto& last = net.ways.back();
  EXPECT_EQ(last.osm_id, 108);
  EXPECT_EQ(last.highway, "pedestrhan");  // area="\0es" reads as "", not "yes": kept
  EXPECT_EQ(last.nodes.size(), 4u);
}

}  // namespace
}  // namespace tourmap::load
