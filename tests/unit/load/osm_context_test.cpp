// Context layers from OSM (load/osm_context.hpp): areas through libosmium's assembler, lines,
// places, and the sea closed from the coastline along the extract's bounds (coastline_sea.hpp).

#include "load/osm_context.hpp"
#include "geo/polygon.hpp"
#include "load/coastline_sea.hpp"
#include "load/load_error.hpp"
#include "load/osm_input.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"
#include "util/stop.hpp"

#include <gtest/gtest.h>
#include <osmium/builder/osm_object_builder.hpp>
#include <osmium/memory/buffer.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace tourmap::load {
namespace {

using model::ContextAreaKind;
using model::ContextLineKind;
using model::ContextPlaceKind;
using test::data_file;

// An .osm document: <bounds> when `bounds` is set, then `body`.
std::string osm(const std::string& body, bool bounds = true) {
  return std::string(R"(<?xml version='1.0' encoding='UTF-8'?><osm version="0.6">)") +
         (bounds ? R"(<bounds minlat="0" minlon="0" maxlat="1" maxlon="1"/>)" : "") + body + "</osm>";
}

std::string node(int id, double lon, double lat, const std::string& tags = "") {
  std::ostringstream out;
  out << "<node id=\"" << id << "\" lat=\"" << lat << "\" lon=\"" << lon << "\"" << (tags.empty() ? "/>" : ">") << tags
      << (tags.empty() ? "" : "</node>");
  return out.str();
}

std::string way(int id, std::initializer_list<int> nodes, const std::string& tags) {
  std::string out = "<way id=\"" + std::to_string(id) + "\">";
  for (int n : nodes) out += "<nd ref=\"" + std::to_string(n) + "\"/>";
  return out + tags + "</way>";
}

std::string tag(const std::string& k, const std::string& v) { return "<tag k=\"" + k + "\" v=\"" + v + "\"/>"; }

geo::Polygon polygon_of(const model::ContextArea& area) {
  return {area.rings.front(), std::vector<std::vector<geo::LonLat>>(area.rings.begin() + 1, area.rings.end())};
}

// Containment by CGAL (geo::PolygonSet), independent of the loader's own ring tests.
bool covers(const model::ContextArea& area, geo::LonLat p) { return geo::PolygonSet({polygon_of(area)}).contains(p); }

std::vector<const model::ContextArea*> areas_of(const model::ContextLayers& layers, ContextAreaKind kind) {
  std::vector<const model::ContextArea*> out;
  for (const auto& area : layers.areas)
    if (area.kind == kind) out.push_back(&area);
  return out;
}

bool any_covers(const model::ContextLayers& layers, ContextAreaKind kind, geo::LonLat p) {
  const auto areas = areas_of(layers, kind);
  return std::any_of(areas.begin(), areas.end(), [&](const auto* area) { return covers(*area, p); });
}

TEST(OsmContext, KindNamesAreStable) {
  EXPECT_EQ(model::name_of(ContextAreaKind::sea), "sea");
  EXPECT_EQ(model::name_of(ContextAreaKind::building), "building");
  EXPECT_EQ(model::name_of(ContextLineKind::railway), "railway");
  EXPECT_EQ(model::name_of(ContextPlaceKind::neighbourhood), "neighbourhood");
  for (std::size_t i = 0; i < model::kContextAreaKinds; ++i)
    EXPECT_EQ(model::area_kind_named(model::kContextAreaKindNames[i]), static_cast<ContextAreaKind>(i));
  EXPECT_EQ(model::line_kind_named("canal"), ContextLineKind::canal);
  EXPECT_EQ(model::place_kind_named("town"), ContextPlaceKind::town);
  EXPECT_FALSE(model::area_kind_named("lava").has_value());
}

TEST(OsmContext, ClosedWayPark) {
  test::TempDir dir;
  const auto path = dir.write("park.osm", osm(node(1, 0.2, 0.2) + node(2, 0.2, 0.4) + node(3, 0.4, 0.4) +
                                              node(4, 0.4, 0.2) +  // drawn clockwise
                                              way(10, {1, 2, 3, 4, 1}, tag("leisure", "park") + tag("name", "P"))));
  OsmContextStats stats;
  const auto layers = load_osm_context(path, &stats);
  ASSERT_EQ(layers.areas.size(), 1u);
  const auto& park = layers.areas[0];
  EXPECT_EQ(park.kind, ContextAreaKind::park);
  ASSERT_EQ(park.rings.size(), 1u);
  EXPECT_EQ(park.rings[0].size(), 4u);          // no repeated closing point
  EXPECT_GT(signed_area2(park.rings[0]), 0.0);  // outer ring counter-clockwise
  EXPECT_TRUE(covers(park, {0.3, 0.3}));
  EXPECT_EQ(stats.areas[static_cast<std::size_t>(ContextAreaKind::park)], 1u);
  EXPECT_EQ(stats.points, 4u);
  EXPECT_EQ(stats.failed_areas, 0u);
  EXPECT_TRUE(layers.lines.empty());
  EXPECT_TRUE(layers.places.empty());
}

TEST(OsmContext, MultipolygonLakeWithIslandHole) {
  test::TempDir dir;
  const std::string body =
      node(1, 0.1, 0.1) + node(2, 0.9, 0.1) + node(3, 0.9, 0.9) + node(4, 0.1, 0.9) +  // outer
      node(5, 0.4, 0.4) + node(6, 0.6, 0.4) + node(7, 0.6, 0.6) + node(8, 0.4, 0.6) +  // island
      way(20, {1, 2, 3, 4, 1}, "") + way(21, {5, 6, 7, 8, 5}, tag("place", "islet")) +
      R"(<relation id="30"><member type="way" ref="20" role="outer"/><member type="way" ref="21" role="inner"/>)" +
      tag("type", "multipolygon") + tag("natural", "water") + tag("name", "Lake") + "</relation>" +
      // A building (closed way) and a broken multipolygon: its only way does not close.
      node(11, 0.2, 0.2) + node(12, 0.25, 0.2) + node(13, 0.25, 0.25) + node(14, 0.2, 0.25) +
      way(40, {11, 12, 13, 14, 11}, tag("building", "yes")) + way(41, {11, 12, 13, 14}, "") +
      R"(<relation id="31"><member type="way" ref="41" role="outer"/>)" + tag("type", "multipolygon") +
      tag("landuse", "forest") + "</relation>";
  const auto path = dir.write("lake.osm", osm(body));
  OsmContextStats stats;
  const auto layers = load_osm_context(path, &stats);
  const auto lakes = areas_of(layers, ContextAreaKind::water);
  ASSERT_EQ(lakes.size(), 1u);
  const auto& lake = *lakes[0];
  ASSERT_EQ(lake.rings.size(), 2u);
  EXPECT_GT(signed_area2(lake.rings[0]), 0.0);  // outer counter-clockwise
  EXPECT_LT(signed_area2(lake.rings[1]), 0.0);  // hole clockwise
  EXPECT_TRUE(covers(lake, {0.2, 0.5}));
  EXPECT_FALSE(covers(lake, {0.5, 0.5}));  // on the island
  EXPECT_EQ(areas_of(layers, ContextAreaKind::building).size(), 1u);
  EXPECT_TRUE(areas_of(layers, ContextAreaKind::forest).empty());
  EXPECT_EQ(stats.failed_areas, 1u);  // the forest
  EXPECT_EQ(stats.osm_relations, 2u);
}

TEST(OsmContext, RiverRailwayAndPlaces) {
  test::TempDir dir;
  const std::string body =
      node(1, 0.1, 0.5) + node(2, 0.5, 0.52) + node(3, 0.9, 0.5) + node(4, 0.1, 0.2) + node(5, 0.9, 0.2) +
      way(10, {1, 2, 3}, tag("waterway", "river") + tag("name", "Test River")) +
      way(11, {4, 5}, tag("railway", "rail") + tag("name", "Line")) +
      way(12, {4, 5}, tag("railway", "subway") + tag("tunnel", "yes")) +
      way(13, {4, 5}, tag("railway", "abandoned")) +                     // left out
      way(14, {4, 5}, tag("railway", "rail") + tag("disused", "yes")) +  // left out
      way(15, {1, 99, 2, 3}, tag("waterway", "stream")) +                // split at the missing node
      node(20, 0.3, 0.7, tag("place", "town") + tag("name", "Townsville") + tag("population", "12,345")) +
      node(21, 0.6, 0.7, tag("place", "village") + tag("name", "Zürich-Örlikon")) +
      node(22, 0.7, 0.7, tag("place", "city")) +  // no name: left out
      node(23, 0.8, 0.7, tag("place", "city") + tag("name", "Big") + tag("population", "3500000"));
  const auto path = dir.write("lines.osm", osm(body));
  OsmContextStats stats;
  const auto layers = load_osm_context(path, &stats);
  ASSERT_EQ(layers.lines.size(), 4u);
  const auto& river = layers.lines[0];
  EXPECT_EQ(river.kind, ContextLineKind::river);
  EXPECT_EQ(river.name, "Test River");
  EXPECT_EQ(river.points.size(), 3u);
  EXPECT_FALSE(river.tunnel);
  EXPECT_EQ(layers.lines[1].kind, ContextLineKind::railway);
  EXPECT_EQ(layers.lines[1].name, "Line");
  EXPECT_EQ(layers.lines[2].kind, ContextLineKind::railway);
  EXPECT_TRUE(layers.lines[2].tunnel);
  EXPECT_EQ(layers.lines[3].kind, ContextLineKind::stream);
  EXPECT_EQ(layers.lines[3].points.size(), 2u);  // 2-3; 1 alone is no line
  EXPECT_EQ(stats.lines[static_cast<std::size_t>(ContextLineKind::railway)], 2u);

  ASSERT_EQ(layers.places.size(), 3u);
  const auto& town = layers.places[0];
  EXPECT_EQ(town.kind, ContextPlaceKind::town);
  EXPECT_EQ(town.name, "Townsville");
  EXPECT_DOUBLE_EQ(town.pos.lon, 0.3);
  EXPECT_DOUBLE_EQ(town.pos.lat, 0.7);
  EXPECT_EQ(town.rank, 13);                            // town 1, population 10^4-10^5: step 3
  EXPECT_EQ(layers.places[1].name, "Zürich-Örlikon");  // UTF-8 kept as is
  EXPECT_EQ(layers.places[1].rank, 38);                // village 3, no population
  EXPECT_EQ(layers.places[2].rank, 1);                 // city 0, 10^6-10^7: step 1
  EXPECT_LT(layers.places[2].rank, town.rank);
  EXPECT_LT(town.rank, layers.places[1].rank);
}

// Land on the left of the coastline, water on its right: drawn west to east, the sea is south.
std::string coast_across(const std::string& extra = "") {
  return node(101, -0.1, 0.5) + node(102, 0.5, 0.55) + node(103, 0.98, 0.5) +  // leaves west, ends near east
         way(1001, {101, 102}, tag("natural", "coastline")) + way(1002, {102, 103}, tag("natural", "coastline")) +
         extra;
}

TEST(OsmContext, CoastlineClosedAlongTheBoundsIntoSea) {
  test::TempDir dir;
  const auto path = dir.write("coast.osm", osm(coast_across()));
  OsmContextStats stats;
  const auto layers = load_osm_context(path, &stats);
  const auto seas = areas_of(layers, ContextAreaKind::sea);
  ASSERT_EQ(seas.size(), 1u);
  EXPECT_EQ(&layers.areas.front(), seas[0]);  // sea first
  EXPECT_EQ(seas[0]->rings.size(), 1u);
  EXPECT_GT(signed_area2(seas[0]->rings[0]), 0.0);
  EXPECT_TRUE(covers(*seas[0], {0.5, 0.2}));
  EXPECT_TRUE(covers(*seas[0], {0.99, 0.01}));  // the south-east corner
  EXPECT_FALSE(covers(*seas[0], {0.5, 0.8}));
  EXPECT_FALSE(covers(*seas[0], {0.5, 0.56}));  // just north of the coast at its bend (0.55)
  EXPECT_EQ(stats.coastline_ways, 2u);
  EXPECT_EQ(stats.coastline_chains, 1u);
  EXPECT_EQ(stats.sea_rings, 1u);
  EXPECT_EQ(stats.broken_coastline_chains, 0u);
  // Inside the box the sea lies within the bounds.
  for (const auto& p : seas[0]->rings[0]) {
    EXPECT_GE(p.lon, 0.0);
    EXPECT_LE(p.lon, 1.0);
  }

  // Drawn east to west instead, the sea is north.
  const auto reversed =
      dir.write("reversed.osm", osm(node(101, -0.1, 0.5) + node(102, 0.5, 0.55) + node(103, 0.98, 0.5) +
                                    way(1001, {103, 102, 101}, tag("natural", "coastline"))));
  const auto north = load_osm_context(reversed);
  ASSERT_EQ(areas_of(north, ContextAreaKind::sea).size(), 1u);
  EXPECT_TRUE(any_covers(north, ContextAreaKind::sea, {0.5, 0.8}));
  EXPECT_FALSE(any_covers(north, ContextAreaKind::sea, {0.5, 0.2}));
}

TEST(OsmContext, IslandInTheSeaIsAHole) {
  test::TempDir dir;
  // Counter-clockwise: the land inside, on the left.
  const std::string island = node(201, 0.4, 0.1) + node(202, 0.6, 0.1) + node(203, 0.6, 0.3) + node(204, 0.4, 0.3) +
                             way(2001, {201, 202, 203}, tag("natural", "coastline")) +
                             way(2002, {203, 204, 201}, tag("natural", "coastline"));
  const auto path = dir.write("island.osm", osm(coast_across(island)));
  OsmContextStats stats;
  const auto layers = load_osm_context(path, &stats);
  const auto seas = areas_of(layers, ContextAreaKind::sea);
  ASSERT_EQ(seas.size(), 1u);
  ASSERT_EQ(seas[0]->rings.size(), 2u);
  EXPECT_LT(signed_area2(seas[0]->rings[1]), 0.0);
  EXPECT_FALSE(covers(*seas[0], {0.5, 0.2}));  // on the island
  EXPECT_TRUE(covers(*seas[0], {0.5, 0.05}));
  EXPECT_TRUE(covers(*seas[0], {0.2, 0.2}));
  EXPECT_EQ(stats.islands, 1u);
  EXPECT_EQ(stats.coastline_chains, 2u);

  // An island alone in the box: the box is sea around it.
  const auto alone = load_osm_context(dir.write("alone.osm", osm(island)));
  const auto open_sea = areas_of(alone, ContextAreaKind::sea);
  ASSERT_EQ(open_sea.size(), 1u);
  EXPECT_EQ(open_sea[0]->rings.size(), 2u);
  EXPECT_TRUE(covers(*open_sea[0], {0.9, 0.9}));
  EXPECT_FALSE(covers(*open_sea[0], {0.5, 0.2}));
}

TEST(OsmContext, BrokenCoastlineMakesNoSea) {
  test::TempDir dir;
  // Enters from the west and stops in the middle of the box (a gap in the data).
  const auto path = dir.write("broken.osm", osm(node(101, 0.0, 0.5) + node(102, 0.3, 0.55) + node(103, 0.5, 0.5) +
                                                way(1001, {101, 102, 103}, tag("natural", "coastline"))));
  OsmContextStats stats;
  const auto layers = load_osm_context(path, &stats);
  EXPECT_TRUE(areas_of(layers, ContextAreaKind::sea).empty());
  EXPECT_EQ(stats.broken_coastline_chains, 1u);
  EXPECT_EQ(stats.sea_rings, 0u);

  // One broken chain spoils the crossing ones: which side is sea near the gap is unknown.
  const auto mixed = dir.write("mixed.osm", osm(coast_across(node(301, 0.0, 0.2) + node(302, 0.3, 0.2) +
                                                             way(3001, {301, 302}, tag("natural", "coastline")))));
  const auto none = load_osm_context(mixed, &stats);
  EXPECT_TRUE(areas_of(none, ContextAreaKind::sea).empty());
  EXPECT_EQ(stats.broken_coastline_chains, 1u);
}

TEST(OsmContext, CoastlineWithoutHeaderBoundsUsesTheNodesBox) {
  test::TempDir dir;
  // The nodes span 0..1 (the corners); the coastline runs from the west side to the east side.
  const std::string body = node(1, 0, 0) + node(2, 1, 1) + node(101, 0.0, 0.5) + node(102, 0.5, 0.55) +
                           node(103, 1.0, 0.5) + way(1001, {101, 102, 103}, tag("natural", "coastline"));
  const auto layers = load_osm_context(dir.write("nobounds.osm", osm(body, false)));
  ASSERT_EQ(areas_of(layers, ContextAreaKind::sea).size(), 1u);
  EXPECT_TRUE(any_covers(layers, ContextAreaKind::sea, {0.5, 0.2}));
  EXPECT_FALSE(any_covers(layers, ContextAreaKind::sea, {0.5, 0.8}));
}

TEST(OsmContext, CoastlineDrawnTheWrongWayMakesNoSea) {
  // Two crossing chains that both have the water on the same side of the box's middle: along
  // the box, end follows end.
  std::vector<CoastlineWay> ways = {{{1, 2}, {{0.0, 0.3}, {1.0, 0.3}}}, {{3, 4}, {{1.0, 0.7}, {0.0, 0.7}}}};
  const geo::BBox box{0, 0, 1, 1};
  auto ok = sea_from_coastlines(ways, box);
  // Water south of the first and north of the second: two seas, land between.
  ASSERT_EQ(ok.seas.size(), 2u);
  EXPECT_EQ(ok.broken_chains, 0u);
  std::swap(ways[1].node_ids[0], ways[1].node_ids[1]);
  std::swap(ways[1].points[0], ways[1].points[1]);
  const auto wrong = sea_from_coastlines(ways, box);
  EXPECT_TRUE(wrong.seas.empty());
  EXPECT_EQ(wrong.broken_chains, 2u);
}

TEST(OsmContext, CoastlineCrossingTheBoxSeveralTimes) {
  // A peninsula poking into the box from the south and leaving again: the sea is the box
  // outside it (the coastline runs up its west side and down its east side... land on the left).
  const std::vector<CoastlineWay> ways = {
      {{1, 2, 3, 4}, {{0.6, -0.2}, {0.6, 0.5}, {0.4, 0.5}, {0.4, -0.2}}},
  };
  const auto sea = sea_from_coastlines(ways, geo::BBox{0, 0, 1, 1});
  ASSERT_EQ(sea.seas.size(), 1u);
  const geo::PolygonSet set(sea.seas);
  EXPECT_FALSE(set.contains({0.5, 0.2}));  // on the peninsula
  EXPECT_TRUE(set.contains({0.5, 0.8}));
  EXPECT_TRUE(set.contains({0.1, 0.1}));
  EXPECT_TRUE(set.contains({0.9, 0.1}));
}

TEST(OsmContext, MalformedTagListsAreRecognised) {
  osmium::memory::Buffer buffer{1024, osmium::memory::Buffer::auto_grow::yes};
  {
    osmium::builder::TagListBuilder builder{buffer};
    builder.add_tag("natural", 7, "water", 5);
  }
  buffer.commit();
  {
    osmium::builder::TagListBuilder builder{buffer};
    builder.add_tag("natural", 7, "wa\0ter", 6);  // as libosmium's PBF reader copies it
  }
  buffer.commit();
  auto it = buffer.select<osmium::TagList>().begin();
  const auto& good = *it++;
  const auto& bad = *it;
  EXPECT_TRUE(well_formed_tags(good));
  EXPECT_STREQ(tag_value(good, "natural"), "water");
  EXPECT_FALSE(well_formed_tags(bad));
}

TEST(OsmContext, LimitsAndErrors) {
  test::TempDir dir;
  const auto path =
      dir.write("lake.osm", osm(node(1, 0.1, 0.1) + node(2, 0.9, 0.1) + node(3, 0.9, 0.9) + way(20, {1, 2, 3, 1}, "") +
                                R"(<relation id="30"><member type="way" ref="20" role="outer"/>)" +
                                tag("type", "multipolygon") + tag("natural", "water") + "</relation>"));
  ImportLimits limits;
  limits.max_context_points = 2;
  try {
    load_osm_context(path, nullptr, limits);
    FAIL() << "expected LimitExceeded";
  } catch (const LimitExceeded& e) {
    EXPECT_EQ(e.limit(), "max_context_points");
  }
  limits = {};
  limits.max_osm_relations = 0;
  try {
    load_osm_context(path, nullptr, limits);
    FAIL() << "expected LimitExceeded";
  } catch (const LimitExceeded& e) {
    EXPECT_EQ(e.limit(), "max_osm_relations");
  }
  EXPECT_EQ(load_osm_context(path).areas.size(), 1u);

  EXPECT_THROW(load_osm_context("/nonexistent.osm"), LoadError);
  std::ifstream in(data_file("roads/krems.osm.gz"), std::ios::binary);
  std::stringstream whole;
  whole << in.rdbuf();
  const auto cut = dir.write("cut.osm.gz", whole.str().substr(0, whole.str().size() / 2));
  try {
    load_osm_context(cut);
    FAIL() << "expected LoadError";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read OSM data"), std::string::npos) << e.what();
  }
}

// The input is bounded and stoppable as the road loader's (the same OsmInput), and failed loads
// leave no descriptor or spool file behind.
TEST(OsmContext, BoundedStoppableAndLeavesNothingOpen) {
  auto open_fds = [] {
    return std::distance(std::filesystem::directory_iterator("/proc/self/fd"), std::filesystem::directory_iterator());
  };
  const auto before = open_fds();
  ImportLimits limits;
  limits.max_osm_decompressed_bytes = 100'000;
  try {
    load_osm_context(data_file("roads/monaco.osm.gz"), nullptr, limits);
    FAIL() << "expected LimitExceeded";
  } catch (const LimitExceeded& e) {
    EXPECT_EQ(e.limit(), "max_osm_decompressed_bytes");
  }
  limits = {};
  limits.max_osm_ways = 100;
  EXPECT_THROW(load_osm_context(data_file("roads/liechtenstein-latest.osm.pbf"), nullptr, limits), LimitExceeded);
  {
    util::StopToken expired;
    expired.deadline = util::StopToken::Clock::now() - std::chrono::seconds(1);
    util::StopScope scope(expired);
    EXPECT_THROW(load_osm_context(data_file("roads/West-Oakland.osm.bz2")), util::Stopped);
    EXPECT_THROW(load_osm_context(data_file("roads/liechtenstein-latest.osm.pbf")), util::Stopped);
  }
  test::TempDir dir;
  std::stringstream whole;
  {
    std::ifstream in(data_file("roads/liechtenstein-latest.osm.pbf"), std::ios::binary);
    whole << in.rdbuf();
  }
  const auto cut = dir.write("cut.osm.pbf", whole.str().substr(0, whole.str().size() / 3));
  for (int i = 0; i < 5; ++i) EXPECT_THROW(load_osm_context(cut), LoadError);
  EXPECT_EQ(open_fds(), before);
}

// Monaco (no <bounds>: the nodes' box): its coastline runs from the box's west side along the
// shore to the French border near the box's top, with the sea to the south-east.
TEST(OsmContext, MonacoSea) {
  OsmContextStats stats;
  const auto layers = load_osm_context(data_file("roads/monaco.osm.gz"), &stats);
  EXPECT_EQ(stats.coastline_ways, 17u);
  EXPECT_EQ(stats.broken_coastline_chains, 0u);
  ASSERT_GE(stats.sea_rings, 1u);
  EXPECT_TRUE(any_covers(layers, ContextAreaKind::sea, {7.44, 43.72}));       // open sea south-east
  EXPECT_TRUE(any_covers(layers, ContextAreaKind::sea, {7.4255, 43.7355}));   // Port Hercule
  EXPECT_FALSE(any_covers(layers, ContextAreaKind::sea, {7.42, 43.735}));     // La Condamine
  EXPECT_FALSE(any_covers(layers, ContextAreaKind::sea, {7.4187, 43.7316}));  // Monaco-Ville, on the rock
  EXPECT_GT(stats.areas[static_cast<std::size_t>(ContextAreaKind::park)], 0u);
  EXPECT_GT(stats.areas[static_cast<std::size_t>(ContextAreaKind::building)], 900u);
}

TEST(OsmContext, LiechtensteinRhineAndVaduz) {
  OsmContextStats stats;
  const auto layers = load_osm_context(data_file("roads/liechtenstein-latest.osm.pbf"), &stats);
  const bool rhine = std::any_of(layers.lines.begin(), layers.lines.end(), [](const model::ContextLine& line) {
    return line.kind == ContextLineKind::river && line.name == "Rhein";
  });
  EXPECT_TRUE(rhine);
  const auto vaduz = std::find_if(layers.places.begin(), layers.places.end(),
                                  [](const model::ContextPlace& place) { return place.name == "Vaduz"; });
  ASSERT_NE(vaduz, layers.places.end());
  EXPECT_NEAR(vaduz->pos.lon, 9.52, 0.03);
  EXPECT_NEAR(vaduz->pos.lat, 47.14, 0.03);
  EXPECT_FALSE(areas_of(layers, ContextAreaKind::water).empty());
  EXPECT_EQ(stats.sea_rings, 0u);  // landlocked
}

}  // namespace
}  // namespace tourmap::load
