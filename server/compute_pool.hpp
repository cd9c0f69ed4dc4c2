#pragma once
// The compute pool: worker threads that run handlers off the IO threads. The queue is bounded
// (a full queue refuses work, which the server answers with 503 + Retry-After) and each task
// carries a deadline so that work queued too long is refused instead of run late.

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace tourmap::server {

class ComputePool {
 public:
  using Clock = std::chrono::steady_clock;
  // `run(expired)`: expired is true when the deadline passed before a worker got to it.
  using Task = std::function<void(bool expired)>;

  ComputePool(unsigned threads, std::size_t max_queue);
  ~ComputePool();
  ComputePool(const ComputePool&) = delete;
  ComputePool& operator=(const ComputePool&) = delete;

  // False when the queue is full (the task is not taken).
  bool submit(Task task, Clock::time_point deadline);
  // Stops taking work, runs what is queued, joins the workers.
  void shutdown();

  std::size_t queued() const;
  std::size_t busy() const;
  unsigned threads() const { return static_cast<unsigned>(workers_.size()); }

 private:
  void work();

  struct Item {
    Task task;
    Clock::time_point deadline;
  };
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Item> queue_;
  std::size_t max_queue_;
  std::size_t busy_ = 0;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace tourmap::server
