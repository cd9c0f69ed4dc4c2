// The CORS allow-list: parsing --cors-origins and matching Origin headers.

#include "server/cors.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace tourmap::server {
namespace {

TEST(Cors, EmptyListIsOff) {
  CorsPolicy off;
  EXPECT_FALSE(off.enabled());
  EXPECT_FALSE(off.allows("https://maps.example.org"));
  EXPECT_FALSE(CorsPolicy(" , ").enabled());
}

TEST(Cors, AllowsListedOriginsOnly) {
  CorsPolicy p("https://maps.example.org, http://localhost:5173/");
  EXPECT_TRUE(p.enabled());
  EXPECT_TRUE(p.allows("https://maps.example.org"));
  EXPECT_TRUE(p.allows("HTTPS://Maps.Example.org"));  // scheme and host are case-insensitive
  EXPECT_TRUE(p.allows("http://localhost:5173"));
  EXPECT_FALSE(p.allows("http://maps.example.org"));       // other scheme
  EXPECT_FALSE(p.allows("https://maps.example.org:8443"));  // other port
  EXPECT_FALSE(p.allows("https://evil.example.org"));
  EXPECT_FALSE(p.allows("https://maps.example.org.evil.net"));
  EXPECT_FALSE(p.allows(""));
  EXPECT_FALSE(p.allows("null"));
}

TEST(Cors, StarAllowsAnyOriginButNull) {
  CorsPolicy p("*");
  EXPECT_TRUE(p.allows("https://anywhere.example"));
  EXPECT_TRUE(p.allows("http://127.0.0.1:8080"));
  EXPECT_FALSE(p.allows("null"));
  EXPECT_FALSE(p.allows("not an origin"));
}

TEST(Cors, RejectsEntriesThatAreNotOrigins) {
  EXPECT_THROW(CorsPolicy("maps.example.org"), std::invalid_argument);
  EXPECT_THROW(CorsPolicy("https://maps.example.org/app"), std::invalid_argument);
  EXPECT_THROW(CorsPolicy("https://a.example, null"), std::invalid_argument);
  EXPECT_THROW(CorsPolicy("https://"), std::invalid_argument);
}

}  // namespace
}  // namespace tourmap::server
