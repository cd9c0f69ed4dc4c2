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
