#pragma once
// Cooperative stopping of long computations. Whoever runs a request (the server's compute
// pool) installs a StopToken for the running thread with StopScope: the request's deadline,
// and a flag the server sets when the client goes away. Long loops in core/ poll it with
// check_stop(), which throws Stopped; without an installed token (CLI, tests, benchmarks)
// check_stop() never throws and costs one thread-local read.
//
// Why thread-local and not a parameter: the loops that must stop (CG iterations, grid routing,
// cluster rounds, kernel density rasters) sit several calls below the handlers, behind
// signatures that the CLI, the tests and the benchmarks share; a request runs on one thread.

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>

namespace tourmap::util {

struct StopToken {
  using Clock = std::chrono::steady_clock;
  Clock::time_point deadline = Clock::time_point::max();
  const std::atomic<bool>* cancelled = nullptr;  // set when the client went away

  bool client_gone() const { return cancelled && cancelled->load(std::memory_order_relaxed); }
  bool expired() const { return deadline != Clock::time_point::max() && Clock::now() >= deadline; }
  bool stop_requested() const { return client_gone() || expired(); }
  // Seconds left before the deadline (a large number without one; 0 once passed).
  double seconds_left() const {
    if (deadline == Clock::time_point::max()) return 1e9;
    const double s = std::chrono::duration<double>(deadline - Clock::now()).count();
    return s > 0 ? s : 0.0;
  }
};

// Thrown by check_stop(): the computation was abandoned, its partial result is worthless.
class Stopped : public std::runtime_error {
 public:
  enum class Reason { deadline, client_gone };
  explicit Stopped(Reason reason)
      : std::runtime_error(reason == Reason::deadline ? "the computation ran past its deadline"
                                                      : "the client went away"),
        reason(reason) {}
  Reason reason;
};

namespace detail {
inline thread_local const StopToken* current_stop_token = nullptr;
}  // namespace detail

// The token installed for this thread, or null.
inline const StopToken* current_stop() { return detail::current_stop_token; }

// Throws Stopped when the installed token says stop. Cheap: call it once per outer iteration.
inline void check_stop() {
  const StopToken* t = detail::current_stop_token;
  if (!t) return;
  if (t->client_gone()) throw Stopped(Stopped::Reason::client_gone);
  if (t->expired()) throw Stopped(Stopped::Reason::deadline);
}

// Installs `token` for the current thread while in scope (nests: restores the previous one).
class StopScope {
 public:
  explicit StopScope(const StopToken& token) : previous_(detail::current_stop_token) {
    detail::current_stop_token = &token;
  }
  ~StopScope() { detail::current_stop_token = previous_; }
  StopScope(const StopScope&) = delete;
  StopScope& operator=(const StopScope&) = delete;

 private:
  const StopToken* previous_;
};

}  // namespace tourmap::util
