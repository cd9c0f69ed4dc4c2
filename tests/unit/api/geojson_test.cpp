#include "api/geojson.hpp"
#include "api/geojson_in.hpp"
#include "api/roads_in.hpp"

#include <gtest/gtest.h>

namespace tourmap::api {
namespace {

using nlohmann::json;

std::string field_of(const json& value) {
  try {
    parse_polygons(value, "within");
  } catch (const ApiError& e) {
    return e.field;
  }
  return "";
}

TEST(GeoJsonIn, AcceptsPolygonMultiPolygonAndFeature) {
  json poly = {{"type", "Polygon"}, {"coordinates", {{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}}}}};
  EXPECT_EQ(parse_polygons(poly, "within").size(), 1u);
  json multi = {{"type", "MultiPolygon"}, {"coordinates", {poly["coordinates"], poly["coordinates"]}}};
  EXPECT_EQ(parse_polygons(multi, "within").size(), 2u);
  json feature = {{"type", "Feature"}, {"properties", nullptr}, {"geometry", poly}};
  EXPECT_EQ(parse_polygons(feature, "within")[0].outer.size(), 4u);  // closing point dropped
}

TEST(GeoJsonIn, RejectionsNameTheField) {
  EXPECT_EQ(field_of(json::array()), "within");
  EXPECT_EQ(field_of({{"type", "Point"}, {"coordinates", {0, 0}}}), "within.type");
  EXPECT_EQ(field_of({{"type", "Polygon"}}), "within.coordinates");
  // not closed
  EXPECT_EQ(field_of({{"type", "Polygon"}, {"coordinates", {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}}}}),
            "within.coordinates[0]");
  // self-intersecting bow tie
  EXPECT_EQ(field_of({{"type", "Polygon"}, {"coordinates", {{{0, 0}, {1, 1}, {1, 0}, {0, 1}, {0, 0}}}}}),
            "within.coordinates[0]");
  // a position out of range
  EXPECT_EQ(field_of({{"type", "Polygon"}, {"coordinates", {{{0, 0}, {1, 0}, {1, 91}, {0, 1}, {0, 0}}}}}),
            "within.coordinates[0][2]");
  // a string where a number belongs
  EXPECT_EQ(field_of({{"type", "Polygon"}, {"coordinates", {{{0, 0}, {"1", 0}, {1, 1}, {0, 1}, {0, 0}}}}}),
            "within.coordinates[0][1]");
}

TEST(GeoJsonIn, VertexLimitIs413) {
  json ring = json::array();
  for (int i = 0; i < 20; ++i) ring.push_back({std::cos(i * 0.3), std::sin(i * 0.3)});
  ring.push_back(ring[0]);
  try {
    parse_polygons({{"type", "Polygon"}, {"coordinates", {ring}}}, "within", {10});
    FAIL();
  } catch (const ApiError& e) {
    EXPECT_EQ(e.status, 413);
  }
}

// Found with fuzz_roads_in (tests/fuzz/corpus/roads_in/regression-type-number): a "type" that
// is not a string made json::value("type", "") throw type_error out of parse_inline_roads, so
// the deform endpoints answered 500 instead of 400.
TEST(GeoJsonIn, InlineRoadsWithNonStringTypesAre400) {
  for (const char* doc : {R"({"type":1,"features":[]})", R"({"type":null,"features":[]})",
                          R"({"type":"FeatureCollection","features":[{"type":"Feature","geometry":
                              {"type":["LineString"],"coordinates":[[16.36,48.2],[16.37,48.2]]}}]})"}) {
    try {
      parse_inline_roads(json::parse(doc), "roads", 100);
      ADD_FAILURE() << "no ApiError for " << doc;
    } catch (const ApiError& e) {
      EXPECT_EQ(e.status, 400) << doc;
      EXPECT_EQ(e.field.rfind("roads", 0), 0u) << e.field;
    }
  }
}

TEST(GeoJsonOut, SegmentTouchesBox) {
  geo::BBox box{0, 0, 1, 1};
  EXPECT_TRUE(segment_touches({-1, 0.5}, {2, 0.5}, box));   // crosses without an endpoint inside
  EXPECT_TRUE(segment_touches({0.5, 0.5}, {5, 5}, box));
  EXPECT_FALSE(segment_touches({-1, 2}, {2, 3}, box));
  EXPECT_FALSE(segment_touches({2, -1}, {3, 2}, box));
  EXPECT_TRUE(segment_touches({-1, 1}, {1, -1}, box));     // touches the corner
}

TEST(GeoJsonOut, RoadsAreSplitAtTheBBox) {
  RoadNetworkEntry entry;
  entry.info.id = "r";
  entry.net.nodes = {{1, {0.0, 0.0}}, {2, {1.0, 0.0}}, {3, {5.0, 0.0}}, {4, {6.0, 0.0}}, {5, {7.0, 0.0}}};
  entry.net.ways = {{9, "residential", "", {0, 1, 2, 3, 4}}};
  entry.net.edges = model::edges_of(entry.net.ways);
  auto all = nlohmann::json::parse(roads_geojson(entry, std::nullopt, true));
  ASSERT_EQ(all["features"].size(), 1u);
  EXPECT_EQ(all["features"][0]["properties"]["nodes"].size(), 5u);
  // A box around x in [0, 0.5] and one around [6.5, 7]: two separate runs of the same way.
  auto left = nlohmann::json::parse(roads_geojson(entry, geo::BBox{-0.1, -0.1, 0.5, 0.1}, false));
  ASSERT_EQ(left["features"].size(), 1u);
  EXPECT_EQ(left["edges"], 1);
  EXPECT_FALSE(left["features"][0]["properties"].contains("nodes"));
}

}  // namespace
}  // namespace tourmap::api
