#include "api/params.hpp"

#include <gtest/gtest.h>

namespace tourmap::api {
namespace {

void expect_field(const std::function<void()>& f, const std::string& field, int status = 400) {
  try {
    f();
    FAIL() << "expected ApiError for " << field;
  } catch (const ApiError& e) {
    EXPECT_EQ(e.field, field);
    EXPECT_EQ(e.status, status);
  }
}

TEST(Params, BBoxParsesAndValidates) {
  auto box = parse_bbox("16.3,48.1,16.4,48.3", "bbox");
  EXPECT_DOUBLE_EQ(box.min_lon, 16.3);
  EXPECT_DOUBLE_EQ(box.max_lat, 48.3);
  for (std::string bad : {"16.4,48.1,16.3,48.3", "1,2,3", "1,2,3,4,5", "a,b,c,d", "nan,1,2,3", "inf,1,2,3",
                          "1,2,3,1e999", "-181,0,0,1", "0,-91,1,0", "", "1,,2,3"})
    expect_field([&] { parse_bbox(bad, "bbox"); }, "bbox");
  EXPECT_DOUBLE_EQ(parse_bbox_json(nlohmann::json::array({1, 2, 3, 4}), "bbox").max_lat, 4.0);
  expect_field([&] { parse_bbox_json(nlohmann::json::array({1, 2, "3", 4}), "bbox"); }, "bbox");
  expect_field([&] { parse_bbox_json(nlohmann::json::object(), "bbox"); }, "bbox");
}

TEST(Params, Integers) {
  Request req;
  req.query = {{"limit", "20"}, {"bad", "2x"}, {"big", "99999999999999999999"}, {"neg", "-1"}};
  EXPECT_EQ(query_int(req, "limit", 1, 100, 5), 20);
  EXPECT_EQ(query_int(req, "absent", 1, 100, 5), 5);
  expect_field([&] { query_int(req, "bad", 1, 100, 5); }, "bad");
  expect_field([&] { query_int(req, "big", 1, 100, 5); }, "big");
  expect_field([&] { query_int(req, "neg", 0, 100, 5); }, "neg");
}

TEST(Params, Booleans) {
  Request req;
  req.query = {{"a", "true"}, {"b", "0"}, {"c", "maybe"}};
  EXPECT_TRUE(query_bool(req, "a", false));
  EXPECT_FALSE(query_bool(req, "b", true));
  EXPECT_TRUE(query_bool(req, "x", true));
  expect_field([&] { query_bool(req, "c", false); }, "c");
}

TEST(Params, SlugsAndJsonBodies) {
  expect_field([] { require_slug("../etc", "city"); }, "id", 404);
  expect_field([] { require_slug("Vienna", "city"); }, "id", 404);
  Request req{"POST", "/x", {}, {}, std::string("{}"), std::string("text/plain")};
  expect_field([&] { parse_json_body(req); }, "Content-Type", 415);
  req.content_type = "application/json; charset=utf-8";
  EXPECT_TRUE(parse_json_body(req).is_object());
  req.body = "{\"a\":";
  expect_field([&] { parse_json_body(req); }, "body");
  req.body = std::string(100, '[') + std::string(100, ']');
  expect_field([&] { parse_json_body(req); }, "body");  // nesting limit
}

// Found by fuzz_deform_request, fuzz_geojson_in and fuzz_roads_in: for a number beyond double's
// range nlohmann's parser throws out_of_range (406), not parse_error, and it escaped
// parse_json_body: every JSON endpoint answered 500 instead of 400. The first two bodies are the
// fuzzers' inputs (tests/fuzz/corpus/*/regression-number-overflow*).
TEST(Params, JsonNumberTooLargeForADoubleIs400) {
  Request req{"POST", "/x", {}, {}, std::string(), std::string("application/json")};
  for (std::string body :
       {std::string(R"({"roals":"grid","grid":1.7976931348623157e309esbbbbbbbbbbbbbbbbbbbbbbbbbbbbbdges"},"guides":[)"
                    R"({"vertex":0180,-90]6.366,48.206]},{"point":[16.361,48.2],"target":[16.359,48.199]}],)"
                    R"("check_crossings":true,"time_limit_ms":500})"),
        std::string(R"({"bbox":[16.3,48.11e308,16.4,48.3]})"), std::string("[1e309]"), std::string("-1e400")}) {
    req.body = body;
    expect_field([&] { parse_json_body(req); }, "body");
  }
}

}  // namespace
}  // namespace tourmap::api
