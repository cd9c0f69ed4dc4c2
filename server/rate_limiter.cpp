#include "rate_limiter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iterator>

namespace tourmap::server {

RateLimiter::RateLimiter(const Options& options) : options_(options) {
  options_.burst = std::max(1.0, options_.burst);
  options_.max_clients = std::max<std::size_t>(1, options_.max_clients);
  const std::size_t n = std::clamp<std::size_t>(options_.shards, 1, options_.max_clients);
  options_.shards = n;
  shard_capacity_ = options_.max_clients / n;  // >= 1; all shards together hold at most max_clients
  shards_.reserve(n);
  for (std::size_t i = 0; i < n; ++i) shards_.push_back(std::make_unique<Shard>());
}

RateLimiter::Shard& RateLimiter::shard_of(std::string_view client) {
  // Mixed, so the shard does not correlate with the bucket an unordered_map picks from the
  // same hash.
  std::uint64_t h = std::hash<std::string_view>{}(client);
  h ^= h >> 29;
  h *= 0x9E3779B97F4A7C15ull;
  h ^= h >> 32;
  return *shards_[static_cast<std::size_t>(h % shards_.size())];
}

bool RateLimiter::idle(const Bucket& b, Clock::time_point now) const {
  // The bucket was full at last + (burst - tokens) / rate.
  const double since_last = std::chrono::duration<double>(now - b.last).count();
  return since_last - (options_.burst - b.tokens) / options_.rate > options_.idle_s;
}

void RateLimiter::evict_idle_locked(Shard& s, Clock::time_point now) {
  // Least recently seen first. A bucket at the front that is not full yet stops the walk even
  // if one behind it is idle; that one goes at most burst/rate seconds late. Each bucket is
  // dropped once, so this is O(1) per request on average.
  while (!s.lru.empty() && idle(s.lru.front(), now)) {
    s.index.erase(s.lru.front().client);
    s.lru.pop_front();
  }
}

RateLimiter::Decision RateLimiter::acquire(std::string_view client, Clock::time_point now) {
  if (!enabled()) return {};
  Shard& s = shard_of(client);
  std::lock_guard lock(s.mutex);
  evict_idle_locked(s, now);
  auto it = s.index.find(client);
  if (it == s.index.end()) {
    if (s.index.size() >= shard_capacity_) {  // forget the least recently seen client
      s.index.erase(s.lru.front().client);
      s.lru.pop_front();
    }
    s.lru.push_back(Bucket{std::string(client), options_.burst - 1.0, now});
    auto last = std::prev(s.lru.end());
    s.index.emplace(last->client, last);
    return {};
  }
  Bucket& b = *it->second;
  s.lru.splice(s.lru.end(), s.lru, it->second);  // now the most recently seen; iterators stay valid
  const double elapsed = std::max(0.0, std::chrono::duration<double>(now - b.last).count());
  b.tokens = std::min(options_.burst, b.tokens + elapsed * options_.rate);
  b.last = std::max(b.last, now);
  if (b.tokens >= 1.0) {
    b.tokens -= 1.0;
    return {};
  }
  return {false, (1.0 - b.tokens) / options_.rate};
}

void RateLimiter::evict_idle(Clock::time_point now) {
  if (!enabled()) return;
  for (auto& s : shards_) {
    std::lock_guard lock(s->mutex);
    evict_idle_locked(*s, now);
  }
}

std::size_t RateLimiter::tracked() const {
  std::size_t n = 0;
  for (const auto& s : shards_) {
    std::lock_guard lock(s->mutex);
    n += s->index.size();
  }
  return n;
}

long RateLimiter::retry_after_header(double retry_after_s) {
  return std::max(1L, static_cast<long>(std::ceil(retry_after_s)));
}

}  // namespace tourmap::server
