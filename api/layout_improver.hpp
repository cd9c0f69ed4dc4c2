#pragma once
// The background queue of metro layout improvements (api/metro_service.hpp: default layouts are
// answered with the fast layout, and their MIP polish runs here afterwards).

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

namespace tourmap::api {

// The background queue of layout improvements: jobs deduplicated by key, run one at a time
// on one thread (started on first use, so tests, the CLI and benchmarks that never schedule
// one have no thread), at a low CPU priority, with a stop token that request_stop() sets:
// a running MIP's child process is killed within its poll interval (api/mip_runner.hpp) and
// the fast path's loops stop at their next util::check_stop(). No exception leaves a job.
class LayoutImprover {
 public:
  // A job polls `stop` (or installs it in a util::StopToken): set when the improver stops.
  using Job = std::function<void(const std::atomic<bool>& stop)>;
  // pending: that key is already queued or running; refused: stopping (or no thread to be had).
  enum class Admission { queued, pending, refused };
  struct Stats {
    std::size_t queued = 0, running = 0;
    std::uint64_t dropped = 0, failed = 0;  // dropped from a full queue; threw
  };

  explicit LayoutImprover(std::size_t max_queue) : max_queue_(max_queue == 0 ? 1 : max_queue) {}
  ~LayoutImprover() { stop(); }
  LayoutImprover(const LayoutImprover&) = delete;
  LayoutImprover& operator=(const LayoutImprover&) = delete;

  Admission push(const std::string& key, Job job);
  void request_stop();  // refuses new jobs, drops the waiting ones, stops the running one; no wait
  void stop();          // request_stop(), then joins the thread
  Stats stats() const;

 private:
  void work();

  const std::size_t max_queue_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::pair<std::string, Job>> queue_;
  std::string running_;  // the running job's key, empty when idle
  std::atomic<bool> stop_{false};
  std::uint64_t dropped_ = 0, failed_ = 0;
  std::thread thread_;
};

}  // namespace tourmap::api
