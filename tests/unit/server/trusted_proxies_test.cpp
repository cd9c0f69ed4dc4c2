// --trusted-proxies: parsing, and the client address read from X-Forwarded-For.

#include "server/trusted_proxies.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace tourmap::server {
namespace {

TEST(TrustedProxies, EmptyTrustsNobody) {
  TrustedProxies none;
  EXPECT_FALSE(none.enabled());
  EXPECT_FALSE(none.trusts("127.0.0.1"));
  EXPECT_EQ(none.client_of("127.0.0.1", "203.0.113.7"), "127.0.0.1");
}

TEST(TrustedProxies, AddressesAndNetworks) {
  TrustedProxies p("127.0.0.1, 10.0.0.0/8 ,::1,fd00::/8");
  EXPECT_TRUE(p.trusts("127.0.0.1"));
  EXPECT_FALSE(p.trusts("127.0.0.2"));
  EXPECT_TRUE(p.trusts("10.1.2.3"));
  EXPECT_FALSE(p.trusts("11.0.0.1"));
  EXPECT_TRUE(p.trusts("::1"));
  EXPECT_TRUE(p.trusts("fd12::5"));
  EXPECT_FALSE(p.trusts("2001:db8::1"));
  EXPECT_TRUE(p.trusts("::ffff:10.9.8.7"));  // IPv4-mapped peers count as IPv4
  EXPECT_FALSE(p.trusts("not an address"));
}

TEST(TrustedProxies, BadEntriesAreRefused) {
  EXPECT_THROW(TrustedProxies("localhost"), std::invalid_argument);
  EXPECT_THROW(TrustedProxies("10.0.0.0/33"), std::invalid_argument);
  EXPECT_THROW(TrustedProxies("10.0.0.1/8x"), std::invalid_argument);
  try {
    TrustedProxies("127.0.0.1, nginx");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nginx"), std::string::npos);
  }
}

TEST(TrustedProxies, ClientIsTheRightMostUntrustedHop) {
  TrustedProxies p("127.0.0.1, 10.0.0.0/8");
  EXPECT_EQ(p.client_of("127.0.0.1", "203.0.113.7"), "203.0.113.7");
  // The client wrote the left entry itself: it cannot choose its address that way.
  EXPECT_EQ(p.client_of("127.0.0.1", "1.2.3.4, 203.0.113.7"), "203.0.113.7");
  // Through two trusted proxies.
  EXPECT_EQ(p.client_of("127.0.0.1", "198.51.100.2, 10.0.0.5"), "198.51.100.2");
  // Every hop trusted: the left-most one is the origin.
  EXPECT_EQ(p.client_of("127.0.0.1", "10.0.0.9, 10.0.0.5"), "10.0.0.9");
}

TEST(TrustedProxies, UntrustedPeersAndGarbageKeepThePeer) {
  TrustedProxies p("127.0.0.1");
  EXPECT_EQ(p.client_of("198.51.100.9", "203.0.113.7"), "198.51.100.9");  // a client cannot spoof
  EXPECT_EQ(p.client_of("127.0.0.1", ""), "127.0.0.1");
  EXPECT_EQ(p.client_of("127.0.0.1", "203.0.113.7, <script>"), "127.0.0.1");
  EXPECT_EQ(p.client_of("127.0.0.1", ",,"), "127.0.0.1");
}

}  // namespace
}  // namespace tourmap::server
