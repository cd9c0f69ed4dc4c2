// multipart/form-data bodies: parts by name with their bytes (binary, with CRLFs inside),
// and a 400 naming the body for every malformed shape.

#include "api/multipart.hpp"

#include <gtest/gtest.h>

namespace tourmap::api {
namespace {

const std::string kType = "multipart/form-data; boundary=\"XyZ\"";

TEST(Multipart, PartsByNameWithBinaryBytes) {
  const std::string binary("\r\n--XY\0\x01\r\n", 11);
  const std::string body = "preamble\r\n--XyZ\r\nContent-Disposition: form-data; name=\"osm\"; filename=\"a.pbf\"\r\n"
                           "Content-Type: application/octet-stream\r\n\r\n" + binary +
                           "\r\n--XyZ\r\ncontent-disposition: form-data; name=gtfs\r\n\r\nPK\r\n--XyZ--\r\nepilogue";
  EXPECT_TRUE(is_multipart(kType));
  EXPECT_FALSE(is_multipart("application/octet-stream"));
  const auto parts = parse_multipart(body, kType);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].name, "osm");
  EXPECT_EQ(parts[0].filename, "a.pbf");
  EXPECT_EQ(parts[0].data, binary);
  EXPECT_EQ(parts[1].name, "gtfs");
  EXPECT_EQ(parts[1].data, "PK");
}

TEST(Multipart, MalformedBodiesAreBadRequests) {
  const std::string part = "--XyZ\r\nContent-Disposition: form-data; name=\"a\"\r\n\r\nx\r\n";
  std::string many;
  for (int i = 0; i < 9; ++i) many += part;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"multipart/form-data", part + "--XyZ--"},                        // no boundary
      {"multipart/form-data; boundary=" + std::string(71, 'a'), part},  // boundary too long
      {kType, "no delimiter at all"},
      {kType, part},                                                     // no closing delimiter
      {kType, "--XyZ\r\nContent-Type: text/plain\r\n\r\nx\r\n--XyZ--"},  // no name
      {kType, "--XyZ\r\nContent-Disposition: form-data; name=\"a\"x\r\n--XyZ--"},  // no header end
      {kType, "--XyZ junk"},
      {kType, many + "--XyZ--"},  // more than kMaxMultipartParts
      {kType, "--XyZ\r\nContent-Disposition: form-data; name=\"a\r\n\r\nx\r\n--XyZ--"},  // open quote
  };
  for (const auto& [type, body] : cases) {
    try {
      parse_multipart(body, type);
      ADD_FAILURE() << "accepted: " << body.substr(0, 80);
    } catch (const ApiError& e) {
      EXPECT_EQ(e.status, 400) << body.substr(0, 80);
      EXPECT_EQ(e.field, "body");
    }
  }
}

}  // namespace
}  // namespace tourmap::api
