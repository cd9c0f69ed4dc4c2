// The per-client token buckets: burst, refill, Retry-After, idle eviction, the cap on tracked
// addresses, and exact accounting under concurrent use. Time is driven by the test.

#include "server/rate_limiter.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace tourmap::server {
namespace {

using namespace std::chrono_literals;
using Clock = RateLimiter::Clock;

RateLimiter::Options opts(double rate, double burst, std::size_t max_clients = 100'000, std::size_t shards = 16) {
  RateLimiter::Options o;
  o.rate = rate;
  o.burst = burst;
  o.max_clients = max_clients;
  o.shards = shards;
  return o;
}

int allowed(RateLimiter& l, const std::string& client, Clock::time_point at, int tries) {
  int n = 0;
  for (int i = 0; i < tries; ++i) n += l.acquire(client, at).allowed ? 1 : 0;
  return n;
}

TEST(RateLimiter, BurstThenRefusalWithRetryAfter) {
  RateLimiter l(opts(5, 5));
  const auto t0 = Clock::time_point{} + 1000s;
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(l.acquire("10.0.0.1", t0).allowed) << i;
  auto d = l.acquire("10.0.0.1", t0);
  EXPECT_FALSE(d.allowed);
  EXPECT_NEAR(d.retry_after_s, 0.2, 1e-9);  // one token every 1/5 s
  EXPECT_EQ(RateLimiter::retry_after_header(d.retry_after_s), 1);
  // Another address has its own bucket.
  EXPECT_EQ(allowed(l, "2001:db8::1", t0, 10), 5);
  EXPECT_EQ(l.tracked(), 2u);
}

TEST(RateLimiter, RefillsAtTheRateUpToTheBurst) {
  RateLimiter l(opts(5, 5));
  const auto t0 = Clock::time_point{} + 1000s;
  EXPECT_EQ(allowed(l, "a", t0, 5), 5);
  EXPECT_FALSE(l.acquire("a", t0 + 100ms).allowed);
  // Refused requests take nothing: 0.2 s after the drain there is exactly one token.
  EXPECT_TRUE(l.acquire("a", t0 + 201ms).allowed);
  EXPECT_FALSE(l.acquire("a", t0 + 201ms).allowed);
  EXPECT_EQ(allowed(l, "a", t0 + 1201ms, 10), 5);
  // A long pause fills the bucket, never beyond the burst.
  EXPECT_EQ(allowed(l, "a", t0 + 100s, 10), 5);
}

TEST(RateLimiter, RetryAfterIsWholeSecondsAtLeastOne) {
  RateLimiter l(opts(0.4, 1));
  const auto t0 = Clock::time_point{} + 1000s;
  EXPECT_TRUE(l.acquire("a", t0).allowed);
  auto d = l.acquire("a", t0 + 1s);  // 0.4 of a token there; 0.6 / 0.4 = 1.5 s to go
  EXPECT_FALSE(d.allowed);
  EXPECT_NEAR(d.retry_after_s, 1.5, 1e-9);
  EXPECT_EQ(RateLimiter::retry_after_header(d.retry_after_s), 2);
  EXPECT_EQ(RateLimiter::retry_after_header(0.0), 1);
  EXPECT_EQ(RateLimiter::retry_after_header(0.01), 1);
  EXPECT_EQ(RateLimiter::retry_after_header(1.0), 1);
  EXPECT_EQ(RateLimiter::retry_after_header(1.01), 2);
}

TEST(RateLimiter, ZeroRateDisables) {
  RateLimiter l(opts(0, 1));
  EXPECT_FALSE(l.enabled());
  EXPECT_EQ(allowed(l, "a", Clock::now(), 1000), 1000);
  EXPECT_EQ(l.tracked(), 0u);
}

TEST(RateLimiter, ForgetsBucketsFullForLongerThanTheIdleTime) {
  auto o = opts(10, 10, 100'000, 1);
  o.idle_s = 60;
  RateLimiter l(o);
  const auto t0 = Clock::time_point{} + 1000s;
  EXPECT_TRUE(l.acquire("one", t0).allowed);      // full again at t0 + 0.1 s
  EXPECT_EQ(allowed(l, "drained", t0, 10), 10);  // full again at t0 + 1 s
  l.evict_idle(t0 + 60s);
  EXPECT_EQ(l.tracked(), 2u);
  l.evict_idle(t0 + 60s + 500ms);  // "one" has been full for 60.4 s; "drained" for 59.5 s
  EXPECT_EQ(l.tracked(), 1u);
  // A request (any address in the shard) evicts too.
  EXPECT_TRUE(l.acquire("other", t0 + 61s + 100ms).allowed);
  EXPECT_EQ(l.tracked(), 1u);
  // A forgotten client starts again with a full bucket: the same as if it had been kept.
  EXPECT_EQ(allowed(l, "drained", t0 + 61s + 100ms, 20), 10);
}

TEST(RateLimiter, RecentlySeenDrainedClientsAreKept) {
  auto o = opts(1, 2, 100'000, 1);
  o.idle_s = 60;
  RateLimiter l(o);
  const auto t0 = Clock::time_point{} + 1000s;
  EXPECT_EQ(allowed(l, "a", t0, 5), 2);
  // A client that keeps asking never has a full bucket: it is never forgotten.
  for (int s = 1; s <= 120; ++s) l.acquire("a", t0 + std::chrono::seconds(s) - 1ms);
  l.evict_idle(t0 + 120s);
  EXPECT_EQ(l.tracked(), 1u);
  EXPECT_FALSE(l.acquire("a", t0 + 120s - 1ms).allowed);  // and its bucket is still nearly empty
}

TEST(RateLimiter, CapDropsTheLeastRecentlySeenAddress) {
  RateLimiter l(opts(1, 1, 3, 1));
  const auto t0 = Clock::time_point{} + 1000s;
  EXPECT_TRUE(l.acquire("a", t0).allowed);
  EXPECT_TRUE(l.acquire("b", t0).allowed);
  EXPECT_TRUE(l.acquire("c", t0).allowed);
  EXPECT_FALSE(l.acquire("a", t0).allowed);  // seen again: b is now the least recently seen
  EXPECT_TRUE(l.acquire("d", t0).allowed);   // b is dropped
  EXPECT_EQ(l.tracked(), 3u);
  EXPECT_TRUE(l.acquire("b", t0).allowed);   // b starts afresh; c is dropped
  EXPECT_FALSE(l.acquire("a", t0).allowed);  // a is still tracked (and empty)
  EXPECT_FALSE(l.acquire("d", t0).allowed);
  EXPECT_EQ(l.tracked(), 3u);
}

TEST(RateLimiter, ShardsTogetherNeverExceedTheCap) {
  RateLimiter l(opts(1, 1, 100, 16));
  const auto t0 = Clock::time_point{} + 1000s;
  for (int i = 0; i < 5000; ++i) l.acquire("10.1." + std::to_string(i / 256) + "." + std::to_string(i % 256), t0);
  EXPECT_LE(l.tracked(), 100u);
  EXPECT_GE(l.tracked(), 16u);  // every shard holds its share
}

TEST(RateLimiter, ConcurrentRequestsTakeExactlyTheBurst) {
  RateLimiter l(opts(1, 300));
  const auto t0 = Clock::time_point{} + 1000s;
  std::atomic<int> shared{0}, own{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      const std::string mine = "client-" + std::to_string(t);
      for (int i = 0; i < 1000; ++i) {
        if (l.acquire("shared", t0).allowed) ++shared;
        if (l.acquire(mine, t0).allowed) ++own;
      }
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(shared.load(), 300);
  EXPECT_EQ(own.load(), 4 * 300);
  EXPECT_EQ(l.tracked(), 5u);
}

}  // namespace
}  // namespace tourmap::server
