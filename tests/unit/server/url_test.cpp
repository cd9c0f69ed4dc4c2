#include "server/url.hpp"

#include <gtest/gtest.h>

namespace tourmap::server {
namespace {

TEST(Url, DecodesPathAndQuery) {
  auto t = parse_target("/api/v1/cities/a%20b/pois?bbox=1%2C2%2C3%2C4&q=caf%C3%A9+bar&flag");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->path, "/api/v1/cities/a b/pois");
  EXPECT_EQ(t->query.at("bbox"), "1,2,3,4");
  EXPECT_EQ(t->query.at("q"), "caf\xC3\xA9 bar");
  EXPECT_EQ(t->query.at("flag"), "");
}

TEST(Url, RejectsMalformedEscapesAndNul) {
  EXPECT_FALSE(parse_target("/a%2"));
  EXPECT_FALSE(parse_target("/a%zz"));
  EXPECT_FALSE(parse_target("/a%00b"));
  EXPECT_FALSE(parse_target("relative"));
  EXPECT_FALSE(parse_target("/x?a=%"));
  EXPECT_EQ(parse_target("/a+b")->path, "/a+b");  // '+' is literal in paths
}

}  // namespace
}  // namespace tourmap::server
