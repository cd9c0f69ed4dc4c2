#include "api/json_out.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace tourmap::api {
namespace {

std::string number(double v) {
  std::string out;
  append_number(out, v);
  return out;
}

TEST(JsonOut, NumbersHaveSevenDecimalsAtMost) {
  EXPECT_EQ(number(16.3729903), "16.3729903");
  EXPECT_EQ(number(16.37299034999), "16.3729903");
  EXPECT_EQ(number(-122.3), "-122.3");
  EXPECT_EQ(number(48.0), "48");
  EXPECT_EQ(number(-0.00000001), "0");
  EXPECT_EQ(number(NAN), "null");
  EXPECT_EQ(number(INFINITY), "null");
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(number(1e300)).get<double>(), 1e300);
}

TEST(JsonOut, StringsAreEscapedAndAlwaysValid) {
  std::string out;
  append_string(out, "Stra\xC3\x9F" "e \"A\"\\\n\x01");
  EXPECT_EQ(nlohmann::json::parse(out).get<std::string>(), "Stra\xC3\x9F" "e \"A\"\\\n\x01");
  out.clear();
  append_string(out, "bad \xC3 byte");
  EXPECT_EQ(nlohmann::json::parse(out).get<std::string>(), "bad \xEF\xBF\xBD byte");
}

TEST(JsonOut, FlatPositions) {
  std::string out;
  append_flat_positions(out, {{1.5, 2.25}, {-3, 4}});
  EXPECT_EQ(out, "[1.5,2.25,-3,4]");
  out.clear();
  append_flat_positions(out, {});
  EXPECT_EQ(out, "[]");
}

}  // namespace
}  // namespace tourmap::api

namespace tourmap::api {
namespace {

std::string shortest(double v) {
  std::string out;
  append_double(out, v);
  return out;
}

// append_double: the shortest text that reads back as the same double, in nlohmann's style.
TEST(JsonOut, DoublesAreShortestAndRoundTrip) {
  EXPECT_EQ(shortest(16.3839302), "16.3839302");
  EXPECT_EQ(shortest(48.0), "48.0");
  EXPECT_EQ(shortest(-0.5), "-0.5");
  EXPECT_EQ(shortest(NAN), "null");
  EXPECT_EQ(shortest(-INFINITY), "null");
  for (double v : {0.1 + 0.2, 1e300, -1e-300, 123456789.123456789, 5e-324, 1.7976931348623157e308}) {
    const auto text = shortest(v);
    EXPECT_EQ(nlohmann::json::parse(text).get<double>(), v) << text;
    EXPECT_LE(text.size(), nlohmann::json(v).dump().size()) << text;
  }
}

// append_string appends (never overwrites) and falls back to U+FFFD on bytes that are not UTF-8.
TEST(JsonOut, StringsAppendAfterExistingTextAndRepairBadUtf8) {
  std::string out = "{\"a\":";
  append_string(out, "Stephansdom");
  out += ",\"b\":";
  const char raw[] = "Caf\xc3\xa9 \xff end\x01";
  append_string(out, std::string_view(raw, sizeof raw - 1));
  out += "}";
  auto doc = nlohmann::json::parse(out);
  EXPECT_EQ(doc["a"], "Stephansdom");
  EXPECT_EQ(doc["b"], "Caf\xc3\xa9 \xef\xbf\xbd end\x01");
}

}  // namespace
}  // namespace tourmap::api
