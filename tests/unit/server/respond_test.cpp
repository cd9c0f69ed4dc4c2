#include "server/gzip.hpp"
#include "server/respond.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace tourmap::server {
namespace {

TEST(Gzip, RoundTripsAndNegotiates) {
  std::string text(5000, 'a');
  auto packed = gzip_compress(text);
  EXPECT_LT(packed.size(), 200u);
  EXPECT_EQ(gzip_decompress(packed), text);
  EXPECT_TRUE(accepts_gzip("gzip, deflate, br"));
  EXPECT_TRUE(accepts_gzip("br;q=1.0, gzip;q=0.8"));
  EXPECT_TRUE(accepts_gzip("*"));
  EXPECT_FALSE(accepts_gzip("gzip;q=0"));
  EXPECT_FALSE(accepts_gzip("gzip;q=0.000"));
  EXPECT_FALSE(accepts_gzip("deflate"));
  EXPECT_FALSE(accepts_gzip(""));
}

TEST(Respond, EtagAnd304) {
  Config config;
  api::Response r = api::json_response({{"a", std::string(2000, 'x')}});
  r.cacheable = true;
  RequestFacts facts;
  auto first = finish_response(r, facts, config);
  auto etag = std::string(first[http::field::etag]);
  ASSERT_FALSE(etag.empty());
  EXPECT_EQ(first[http::field::cache_control], "no-cache");
  facts.if_none_match = "\"other\", " + etag;
  auto second = finish_response(r, facts, config);
  EXPECT_EQ(second.result(), http::status::not_modified);
  EXPECT_TRUE(second.body().empty());
  EXPECT_TRUE(etag_matches("*", etag));
  EXPECT_TRUE(etag_matches(etag.substr(2), etag));  // strong form of the same tag
}

TEST(Respond, GzipOnlyWhenAcceptedAndLargeEnough) {
  Config config;
  RequestFacts facts;
  facts.accept_encoding = "gzip";
  auto big = finish_response(api::json_response({{"a", std::string(5000, 'x')}}), facts, config);
  EXPECT_EQ(big[http::field::content_encoding], "gzip");
  EXPECT_EQ(big[http::field::vary], "Accept-Encoding");
  EXPECT_NE(gzip_decompress(big.body()).find("xxxx"), std::string::npos);
  auto small = finish_response(api::json_response({{"a", 1}}), facts, config);
  EXPECT_EQ(small[http::field::content_encoding], "");
  facts.accept_encoding = "";
  auto plain = finish_response(api::json_response({{"a", std::string(5000, 'x')}}), facts, config);
  EXPECT_EQ(plain[http::field::content_encoding], "");
}

TEST(Respond, HeadKeepsLengthWithoutBody) {
  Config config;
  RequestFacts facts;
  facts.method = http::verb::head;
  auto res = finish_response(api::json_response({{"a", 1}}), facts, config);
  EXPECT_TRUE(res.body().empty());
  EXPECT_EQ(res[http::field::content_length], "7");
}

}  // namespace
}  // namespace tourmap::server

namespace tourmap::server {
namespace {

// gzip_compress keeps one compressor per thread and level: nothing carries over between bodies,
// levels do not leak into each other, and threads do not share state.
TEST(Gzip, ReusedStreamsAcrossLevelsAndThreads) {
  const std::string a(5000, 'a'), b = "tourmap " + std::string(3000, 'b');
  for (int round = 0; round < 3; ++round)
    for (int level : {1, 5, 9, 12, -1, 99}) {
      EXPECT_EQ(gzip_decompress(gzip_compress(a, level)), a);
      EXPECT_EQ(gzip_decompress(gzip_compress(b, level)), b);
      EXPECT_EQ(gzip_decompress(gzip_compress("", level)), "");
    }
  std::vector<std::thread> threads;
  std::atomic<int> bad{0};
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      const std::string mine(1000 + 100 * t, static_cast<char>('c' + t));
      for (int i = 0; i < 200; ++i)
        if (gzip_decompress(gzip_compress(mine, 1 + (i % 9))) != mine) ++bad;
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(bad.load(), 0);
}

}  // namespace
}  // namespace tourmap::server
