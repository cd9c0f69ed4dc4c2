#include "api/positions_binary.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace tourmap::api {
namespace {

TEST(PositionsBinary, HeaderJsonPaddingAndOffsets) {
  const std::vector<geo::LonLat> points = {{9.5, 47.1}, {9.6, 47.2}, {9.55, 47.0}};
  const std::string json = R"({"a":1})";  // 7 bytes: one byte of padding
  const auto b = encode_positions_binary(json, points);
  ASSERT_EQ(b.size(), 32u + 8u + 3u * 8u);
  EXPECT_EQ(b.substr(0, 4), "TMDP");
  std::uint32_t version, json_bytes, count;
  double lon0, lat0;
  std::memcpy(&version, b.data() + 4, 4);
  std::memcpy(&json_bytes, b.data() + 8, 4);
  std::memcpy(&count, b.data() + 12, 4);
  std::memcpy(&lon0, b.data() + 16, 8);
  std::memcpy(&lat0, b.data() + 24, 8);
  EXPECT_EQ(version, 1u);
  EXPECT_EQ(json_bytes, 7u);
  EXPECT_EQ(count, 3u);
  EXPECT_DOUBLE_EQ(lon0, 9.55);  // the middle of the bounding box
  EXPECT_DOUBLE_EQ(lat0, 47.1);
  EXPECT_EQ(b.substr(32, 7), json);
  EXPECT_EQ(b[39], '\0');
  for (std::size_t i = 0; i < points.size(); ++i) {
    float dx, dy;
    std::memcpy(&dx, b.data() + 40 + 8 * i, 4);
    std::memcpy(&dy, b.data() + 44 + 8 * i, 4);
    EXPECT_NEAR(lon0 + dx, points[i].lon, 1e-8);
    EXPECT_NEAR(lat0 + dy, points[i].lat, 1e-8);
  }
  // No points: only the header and the JSON.
  EXPECT_EQ(encode_positions_binary("{}", {}).size(), 36u);
}

TEST(PositionsBinary, AcceptHeader) {
  EXPECT_TRUE(accepts_octet_stream("application/octet-stream"));
  EXPECT_TRUE(accepts_octet_stream("Application/Octet-Stream; q=1"));
  EXPECT_TRUE(accepts_octet_stream("application/octet-stream, application/json;q=0.9"));
  EXPECT_TRUE(accepts_octet_stream("application/json;q=0.5,application/octet-stream"));
  EXPECT_TRUE(accepts_octet_stream("application/octet-stream, */*"));  // wildcards count for neither
  EXPECT_FALSE(accepts_octet_stream(""));
  EXPECT_FALSE(accepts_octet_stream("*/*"));
  EXPECT_FALSE(accepts_octet_stream("application/json"));
  EXPECT_FALSE(accepts_octet_stream("application/octet-stream;q=0"));
  EXPECT_FALSE(accepts_octet_stream("application/octet-stream;q=0.5, application/json"));
  EXPECT_FALSE(accepts_octet_stream("application/octet-stream;q=2"));   // not a qvalue
  EXPECT_FALSE(accepts_octet_stream("application/octet-stream;q=0.x"));
  EXPECT_FALSE(accepts_octet_stream(",,;;,"));
}

}  // namespace
}  // namespace tourmap::api
