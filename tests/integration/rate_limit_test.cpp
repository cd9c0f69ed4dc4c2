// Per-client rate limiting (429 with Retry-After) and the CORS allow-list, against a real
// server. The tests run from 127.0.0.1, so they all share one client address.

#include "live_server_suite.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace tourmap::test {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

const std::string kAllowed = "https://maps.example.org";
const std::string kOther = "https://elsewhere.example.net";

// --rate-limit 5 --rate-burst 5: a client may make 5 requests at once, then one every 0.2 s.
class RateLimit : public LiveServerSuite<RateLimit> {
 public:
  static std::vector<std::string> server_flags() {
    return {"--rate-limit", "5", "--rate-burst", "5", "--cors-origins", kAllowed};
  }

 protected:
  // Every test starts with a full bucket (5 tokens come back in 1 s).
  void SetUp() override { std::this_thread::sleep_for(1100ms); }

  // Requests until the first 429; returns how many passed before it (-1: none refused).
  static int passed_before_refusal(HttpResult* refusal, int max_requests = 30) {
    for (int i = 0; i < max_requests; ++i) {
      auto r = live->get("/api/v1/cities");
      if (r.status == 429) {
        if (refusal) *refusal = r;
        return i;
      }
      EXPECT_EQ(r.status, 200) << r.body;
    }
    return -1;
  }
};

TEST_F(RateLimit, BurstPassesThenTooManyRequestsWithRetryAfter) {
  const auto start = Clock::now();
  HttpResult refusal;
  const int passed = passed_before_refusal(&refusal);
  const auto took = Clock::now() - start;
  ASSERT_GE(passed, 5) << "the burst of 5 was not served";
  if (took < 150ms) {
    EXPECT_EQ(passed, 5);  // no token could have come back yet
  }
  EXPECT_EQ(refusal.status, 429);
  const std::string retry = refusal.header("retry-after");
  ASSERT_FALSE(retry.empty());
  EXPECT_GE(std::stoi(retry), 1);
  EXPECT_EQ(refusal.header("content-type"), "application/json");
  auto err = error_of(refusal);
  EXPECT_EQ(err["code"], "rate_limited");
  EXPECT_FALSE(err["message"].get<std::string>().empty());
  EXPECT_TRUE(err["field"].is_null()) << refusal.body;
  // Other methods and paths (static files, unknown paths, POSTs) are limited alike.
  EXPECT_EQ(live->get("/").status, 429);
  EXPECT_EQ(live->get("/api/v1/nothing-here").status, 429);
  EXPECT_EQ(http_request(live->port(), "POST", "/api/v1/cities/vienna/pois/query",
                         {{"Content-Type", "application/json"}}, "{}")
                .status,
            429);
}

TEST_F(RateLimit, HealthAndMetricsAreNeverLimited) {
  ASSERT_GE(passed_before_refusal(nullptr), 5);
  const auto refused = Clock::now();
  for (int i = 0; i < 30; ++i) ASSERT_EQ(live->get("/healthz").status, 200) << i;
  EXPECT_EQ(http_request(live->port(), "HEAD", "/healthz").status, 200);
  auto metrics = live->get("/metrics");
  ASSERT_EQ(metrics.status, 200);
  EXPECT_NE(metrics.body.find(R"(tourmap_http_requests_total{route="rate_limited",method="GET",status="429"})"),
            std::string::npos)
      << metrics.body;
  EXPECT_NE(metrics.body.find("tourmap_rate_limit_clients 1\n"), std::string::npos) << metrics.body;
  // Still limited meanwhile: only the tokens that came back since the refusal (one per 0.2 s;
  // on a slow machine, ASan, the 32 requests above take longer than that) pass, then 429.
  const double waited_s = std::chrono::duration<double>(Clock::now() - refused).count();
  const int passed = passed_before_refusal(nullptr);
  EXPECT_GE(passed, 0) << "30 requests passed";
  EXPECT_LE(passed, static_cast<int>(waited_s * 5) + 1) << "after " << waited_s << " s";
}

TEST_F(RateLimit, RequestsPassAgainAfterAWait) {
  HttpResult refusal;
  ASSERT_GE(passed_before_refusal(&refusal), 5);
  std::this_thread::sleep_for(std::chrono::seconds(std::stoi(refusal.header("retry-after"))) + 100ms);
  EXPECT_EQ(live->get("/api/v1/cities").status, 200);
  std::this_thread::sleep_for(1100ms);  // the whole burst is back
  for (int i = 0; i < 5; ++i) EXPECT_EQ(live->get("/api/v1/cities").status, 200) << i;
}

TEST_F(RateLimit, WebSocketUpgradesAreLimitedToo) {
  ASSERT_GE(passed_before_refusal(nullptr), 5);
  auto answer = raw_exchange(live->port(),
                             "GET /api/v1/events HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\n"
                             "Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
                             "Sec-WebSocket-Version: 13\r\n\r\n",
                             2s);
  EXPECT_EQ(answer.rfind("HTTP/1.1 429", 0), 0u) << answer;
  EXPECT_NE(answer.find("rate_limited"), std::string::npos) << answer;
}

TEST_F(RateLimit, RefusalsCarryCorsHeadersForAnAllowedOrigin) {
  ASSERT_GE(passed_before_refusal(nullptr), 5);
  // A cross-origin script can read the 429 and its Retry-After.
  auto r = live->get("/api/v1/cities", {{"Origin", kAllowed}});
  EXPECT_EQ(r.status, 429);
  EXPECT_EQ(r.header("access-control-allow-origin"), kAllowed);
  EXPECT_NE(r.header("access-control-expose-headers").find("Retry-After"), std::string::npos);
}

// CORS with an allow-list and no rate limit (--rate-limit 0; with a burst of 1 any limit would
// refuse the second request).
class CorsLive : public LiveServerSuite<CorsLive> {
 public:
  static std::vector<std::string> server_flags() {
    return {"--cors-origins", kAllowed + ", http://localhost:5173", "--rate-limit", "0", "--rate-burst", "1"};
  }

 protected:
  static HttpResult preflight(const std::string& origin, const std::string& target = "/api/v1/cities/vienna/pois/query") {
    return http_request(live->port(), "OPTIONS", target,
                        {{"Origin", origin},
                         {"Access-Control-Request-Method", "POST"},
                         {"Access-Control-Request-Headers", "content-type"}});
  }
};

TEST_F(CorsLive, AllowedOriginGetsTheHeader) {
  auto r = live->get("/api/v1/cities", {{"Origin", kAllowed}});
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.header("access-control-allow-origin"), kAllowed);
  EXPECT_NE(r.header("vary").find("Origin"), std::string::npos) << r.header("vary");
  EXPECT_NE(r.header("vary").find("Accept-Encoding"), std::string::npos) << r.header("vary");
  // The script may read the compute time of a cluster query (fetch headers and resource timings).
  auto clusters = live->get("/api/v1/cities/vienna/clusters?m=2", {{"Origin", kAllowed}});
  EXPECT_FALSE(clusters.header("server-timing").empty());
  EXPECT_NE(clusters.header("access-control-expose-headers").find("Server-Timing"), std::string::npos);
  EXPECT_EQ(clusters.header("timing-allow-origin"), kAllowed);
  EXPECT_EQ(live->get("/api/v1/cities", {{"Origin", "http://localhost:5173"}}).header("access-control-allow-origin"),
            "http://localhost:5173");
  // Errors too, so the client can read them.
  auto missing = live->get("/api/v1/cities/atlantis", {{"Origin", kAllowed}});
  EXPECT_EQ(missing.status, 404);
  EXPECT_EQ(missing.header("access-control-allow-origin"), kAllowed);
}

TEST_F(CorsLive, DisallowedOrNoOriginGetsNoCorsHeaders) {
  for (const auto& headers : {std::map<std::string, std::string>{{"Origin", kOther}},
                              std::map<std::string, std::string>{{"Origin", "null"}},
                              std::map<std::string, std::string>{}}) {
    auto r = live->get("/api/v1/cities", headers);
    EXPECT_EQ(r.status, 200);  // served; the browser withholds it from the other origin's script
    for (const auto& [name, value] : r.headers) {
      EXPECT_NE(name.rfind("access-control-", 0), 0u) << name;
      EXPECT_NE(name, "timing-allow-origin");
    }
    EXPECT_NE(r.header("vary").find("Origin"), std::string::npos);  // caches keep answers apart
  }
}

TEST_F(CorsLive, PreflightFromAnAllowedOriginIs204) {
  auto r = preflight(kAllowed);
  EXPECT_EQ(r.status, 204) << r.body;
  EXPECT_TRUE(r.body.empty());
  EXPECT_EQ(r.header("access-control-allow-origin"), kAllowed);
  EXPECT_EQ(r.header("access-control-allow-methods"), "GET, POST, PUT, DELETE, OPTIONS");
  EXPECT_EQ(r.header("access-control-allow-headers"), "Content-Type, Authorization, X-API-Key, If-None-Match");
  EXPECT_EQ(r.header("access-control-max-age"), "600");
  EXPECT_NE(r.header("vary").find("Origin"), std::string::npos);
  // Then the request it announced.
  auto post = http_request(live->port(), "POST", "/api/v1/cities/vienna/pois/query",
                           {{"Content-Type", "application/json"}, {"Origin", kAllowed}}, R"({"limit": 1})");
  EXPECT_EQ(post.status, 200) << post.body;
  EXPECT_EQ(post.header("access-control-allow-origin"), kAllowed);
}

TEST_F(CorsLive, PreflightFromAnotherOriginIs403) {
  auto r = preflight(kOther);
  EXPECT_EQ(r.status, 403);
  auto err = error_of(r);
  EXPECT_EQ(err["code"], "origin_not_allowed");
  EXPECT_EQ(err["field"], "Origin");
  for (const auto& [name, value] : r.headers) EXPECT_NE(name.rfind("access-control-", 0), 0u) << name;
}

TEST_F(CorsLive, OptionsWithoutPreflightHeadersIsRoutedAsBefore) {
  auto r = http_request(live->port(), "OPTIONS", "/api/v1/cities", {{"Origin", kAllowed}});
  EXPECT_EQ(r.status, 405);
  EXPECT_EQ(error_of(r)["field"], "method");
  EXPECT_EQ(r.header("allow"), "GET");
}

TEST(ServeOptions, InvalidRateLimitAndCorsOptionsAreRefusedAtStart) {
  TempDir dir;
  const std::string db = dir.file("t.db");
  struct Bad {
    std::string flag, named;
  };
  for (const Bad& bad : {Bad{"--rate-limit=-1", "--rate-limit"}, Bad{"--rate-limit=inf", "--rate-limit"},
                         Bad{"--rate-burst=0", "--rate-burst"}, Bad{"--cors-origins=maps.example.org", "--cors-origins"},
                         Bad{"--cors-origins=https://maps.example.org/app", "--cors-origins"}}) {
    auto r = run_command({kTourmapBin, "serve", "--db", db, "--port", "0", bad.flag});
    EXPECT_EQ(r.exit_code, 2) << bad.flag << ": " << r.output;
    EXPECT_NE(r.output.find(bad.named), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace tourmap::test
