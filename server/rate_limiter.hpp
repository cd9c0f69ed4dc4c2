#pragma once
// Per-client rate limiting: a token bucket per client address, refilled at `rate` tokens per
// second up to `burst`; a request takes one token or is refused with the time until one is
// there. The table of buckets is bounded: a bucket that has been full for `idle_s` is dropped
// (it is then the same as no bucket), and beyond `max_clients` the least recently seen client
// is dropped (it starts again with a full bucket). Thread-safe: the table is split into
// shards by address, each with its own short lock and an equal share of `max_clients`, so
// "least recently seen" is per shard. Time is passed in, so tests drive it.

#include <chrono>
#include <cstddef>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace tourmap::server {

class RateLimiter {
 public:
  using Clock = std::chrono::steady_clock;

  struct Options {
    double rate = 200.0;              // tokens per second; 0 disables the limiter
    double burst = 400.0;             // bucket size (at least 1)
    double idle_s = 60.0;             // a bucket full for longer than this is forgotten
    std::size_t max_clients = 100'000;  // tracked addresses (least recently seen dropped beyond)
    std::size_t shards = 16;          // independent locks (fewer when max_clients is small)
  };

  struct Decision {
    bool allowed = true;
    double retry_after_s = 0.0;  // when refused: seconds until a token is there (> 0)
  };

  explicit RateLimiter(const Options& options);
  RateLimiter(const RateLimiter&) = delete;
  RateLimiter& operator=(const RateLimiter&) = delete;

  bool enabled() const { return options_.rate > 0.0; }
  const Options& options() const { return options_; }

  // Takes a token from `client`'s bucket at time `now`. Always allowed when disabled.
  Decision acquire(std::string_view client, Clock::time_point now);
  // Drops the buckets that have been full for longer than idle_s (acquire does this too, for
  // its shard).
  void evict_idle(Clock::time_point now);
  // Addresses tracked now.
  std::size_t tracked() const;

  // Retry-After header value for a refusal: whole seconds, at least 1.
  static long retry_after_header(double retry_after_s);

 private:
  struct Bucket {
    std::string client;
    double tokens = 0.0;
    Clock::time_point last;  // when `tokens` was computed
  };
  struct Shard {
    mutable std::mutex mutex;
    std::list<Bucket> lru;  // least recently seen first
    std::unordered_map<std::string_view, std::list<Bucket>::iterator> index;  // keys point into `lru`
  };

  Shard& shard_of(std::string_view client);
  bool idle(const Bucket& b, Clock::time_point now) const;
  void evict_idle_locked(Shard& s, Clock::time_point now);

  Options options_;
  std::size_t shard_capacity_ = 0;
  std::vector<std::unique_ptr<Shard>> shards_;
};

}  // namespace tourmap::server
