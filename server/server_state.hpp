#pragma once
// What every connection shares: configuration, routes, the compute pool, metrics, logs, and
// the registry of live sessions used for graceful shutdown.

#include "access_log.hpp"
#include "compute_pool.hpp"
#include "config.hpp"
#include "cors.hpp"
#include "metrics.hpp"
#include "rate_limiter.hpp"
#include "static_files.hpp"
#include "trusted_proxies.hpp"

#include "api/router.hpp"

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

namespace tourmap::server {

class WsSession;

// A WebSocket endpoint: called on the session's strand when a client connects and for every
// text message it sends.
struct WsEndpoint {
  std::function<void(const std::shared_ptr<WsSession>&)> on_open;
  std::function<void(const std::shared_ptr<WsSession>&, const std::string&)> on_text;
  std::function<void(const std::shared_ptr<WsSession>&)> on_close;
};

// Sessions register here so shutdown can reach them.
class SessionRegistry {
 public:
  using Closer = std::function<void()>;  // asks the session to finish and close
  std::uint64_t add(Closer closer) {
    std::lock_guard lock(mutex_);
    closers_.emplace(++next_, std::move(closer));
    return next_;
  }
  void remove(std::uint64_t id) {
    std::lock_guard lock(mutex_);
    closers_.erase(id);
  }
  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return closers_.size();
  }
  void close_all() {
    std::map<std::uint64_t, Closer> copy;
    {
      std::lock_guard lock(mutex_);
      copy = closers_;
    }
    for (auto& [id, close] : copy) close();
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::uint64_t, Closer> closers_;
  std::uint64_t next_ = 0;
};

struct ServerState {
  explicit ServerState(Config cfg)
      : config(std::move(cfg)),
        compute_pool({config.compute_threads, config.compute_queue, config.max_compute_per_client}),
        read_pool({config.read_threads, config.read_queue, config.max_reads_per_client}),
        access_log(config.access_log),
        static_files(config.web_root),
        rate_limiter(rate_limiter_options(config)),
        cors(config.cors_origins),
        trusted_proxies(config.trusted_proxies) {}

  static RateLimiter::Options rate_limiter_options(const Config& c) {
    RateLimiter::Options o;
    o.rate = c.rate_limit;
    o.burst = c.rate_burst;
    return o;
  }

  Config config;
  api::Router router;
  std::map<std::string, WsEndpoint> ws_endpoints;  // by path
  ComputePool compute_pool;  // Exec::heavy routes
  ComputePool read_pool;     // Exec::light routes
  Metrics metrics;
  AccessLog access_log;
  StaticFiles static_files;
  SessionRegistry http_sessions;
  SessionRegistry ws_sessions;
  RateLimiter rate_limiter;  // per client address, before routing
  CorsPolicy cors;
  TrustedProxies trusted_proxies;  // whose X-Forwarded-For names the client (rate limit, access log)
  // True when the key is an active API key (the write routes need one); unset: no writes.
  std::function<bool(std::string_view key)> verify_api_key;
  std::atomic<bool> stopping{false};
  std::atomic<long> in_flight{0};  // requests read and not yet answered
  std::atomic<std::uint64_t> handler_exceptions{0};  // exceptions that reached an IO thread's run loop
};

}  // namespace tourmap::server
