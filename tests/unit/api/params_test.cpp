#include "api/params.hpp"

#include <gtest/gtest.h>

#include <cmath>

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
  Request req{"POST", "/x", {}, {}, std::string("{}"), std::string("text/plain"), ""};
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
  Request req{"POST", "/x", {}, {}, std::string(), std::string("application/json"), ""};
  for (std::string body :
       {std::string(R"({"roals":"grid","grid":1.7976931348623157e309esbbbbbbbbbbbbbbbbbbbbbbbbbbbbbdges"},"guides":[)"
                    R"({"vertex":0180,-90]6.366,48.206]},{"point":[16.361,48.2],"target":[16.359,48.199]}],)"
                    R"("check_crossings":true,"time_limit_ms":500})"),
        std::string(R"({"bbox":[16.3,48.11e308,16.4,48.3]})"), std::string("[1e309]"), std::string("-1e400")}) {
    req.body = body;
    expect_field([&] { parse_json_body(req); }, "body");
  }
}

// The one format of every refusal: the message starts with the field it names.
TEST(Params, RefusalsNameTheirFieldFirst) {
  const ApiError b = bad("grid.base", "must be between 1 and 64");
  EXPECT_EQ(b.status, 400);
  EXPECT_EQ(b.code, "invalid_parameter");
  EXPECT_EQ(b.field, "grid.base");
  EXPECT_EQ(b.message, "grid.base: must be between 1 and 64");
  const ApiError t = too_large("regions", "at most 32 items");
  EXPECT_EQ(t.status, 413);
  EXPECT_EQ(t.code, "too_large");
  EXPECT_EQ(t.message, "regions: at most 32 items");
  EXPECT_EQ(not_found("id", "city", "atlantis").message, "id: no city 'atlantis'");
  EXPECT_EQ(bad("body", "x", "invalid_json").code, "invalid_json");
}

// A client's text inside a message: bounded, and a NUL cannot cut the message short.
TEST(Params, ShownTextIsBoundedAndPrintable) {
  EXPECT_EQ(shown("vienna"), "vienna");
  EXPECT_EQ(shown(std::string("a\0b\n", 4)), "a\\x00b\\x0a");
  EXPECT_EQ(shown(std::string(100, 'x')), std::string(64, 'x') + "...");
  const ApiError e = bad("scene", "unknown scene '" + shown(std::string("of\0fice", 7)) + "'");
  EXPECT_EQ(e.message, "scene: unknown scene 'of\\x00fice'");  // whole, where what() would stop at the NUL
}

TEST(Params, TypedJsonReaders) {
  using nlohmann::json;
  EXPECT_EQ(json_number(json(2.5), "x", 0, 10), 2.5);
  expect_field([] { json_number(json("2"), "x", 0, 10); }, "x");
  expect_field([] { json_number(json(11), "x", 0, 10); }, "x");
  expect_field([] { json_number(json(std::nan("")), "x", 0, 10); }, "x");
  EXPECT_EQ(json_integer(json(7), "n", 1, 10), 7);
  expect_field([] { json_integer(json(7.5), "n", 1, 10); }, "n");
  expect_field([] { json_integer(json(18446744073709551615ull), "n", 1, 10); }, "n");  // not -1
  EXPECT_TRUE(json_bool(json(true), "b"));
  expect_field([] { json_bool(json(1), "b"); }, "b");
  EXPECT_EQ(json_choice(json("cg"), "solver", {"cholesky", "cg"}), "cg");
  expect_field([] { json_choice(json("lu"), "solver", {"cholesky", "cg"}); }, "solver");
  EXPECT_EQ(json_array(json::array({1, 2}), "a", 1, 2).size(), 2u);
  expect_field([] { json_array(json::array({1, 2, 3}), "a", 1, 2); }, "a", 413);
  expect_field([] { json_array(json::array(), "a", 1, 2); }, "a");
  EXPECT_EQ(json_string(json("abc"), "s", 3), "abc");
  expect_field([] { json_string(json("abcd"), "s", 3); }, "s", 413);
  expect_field([] { reject_unknown(json{{"a", 1}, {"zz", 2}}, "obj", {"a"}); }, "obj.zz");
  EXPECT_EQ(member(json{{"a", 1}}, "a")->get<int>(), 1);
  EXPECT_EQ(member(json{{"a", 1}}, "b"), nullptr);
  EXPECT_EQ(member(json::array(), "a"), nullptr);
}

TEST(Params, QueryNumbersAndChoices) {
  Request req{"GET", "/x", {{"w", "0.5"}, {"f", "topology"}, {"bad", "1e999"}}, {}, "", "", ""};
  EXPECT_EQ(query_number(req, "w", 0, 1, 0.7), 0.5);
  EXPECT_EQ(query_number(req, "missing", 0, 1, 0.7), 0.7);
  expect_field([&] { query_number(req, "bad", 0, 1, 0.7); }, "bad");
  expect_field([&] { query_number(req, "w", 0.6, 1, 0.7); }, "w");
  EXPECT_EQ(query_choice(req, "f", {"geojson", "topology"}, "geojson"), "topology");
  EXPECT_EQ(query_choice(req, "g", {"geojson", "topology"}, "geojson"), "geojson");
  expect_field([&] { query_choice(req, "w", {"geojson", "topology"}, "geojson"); }, "w");
}

}  // namespace
}  // namespace tourmap::api
