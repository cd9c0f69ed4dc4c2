#pragma once
// A compute pool: worker threads that run handlers off the IO threads. The server has two, so
// that cheap reads never wait behind expensive work (layouts, deformations, rasters, imports).
//
// Bounded and fair:
//   - the queue holds at most `max_queue` tasks (beyond: Admission::queue_full, answered 503);
//   - a client (address) may have at most `max_per_client` tasks queued or running (beyond:
//     Admission::client_busy, answered 429); 0 means no cap;
//   - queued tasks are taken round-robin across clients, so one client's burst does not delay
//     another client's single request by more than one task per client ahead of it;
//   - every task has a deadline for starting: a watcher thread hands a task whose deadline
//     passes while it is still queued `run(true)` at once (the server answers 503), so a queued
//     request never waits longer than its deadline, even when every worker is busy for longer.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

namespace tourmap::server {

class ComputePool {
 public:
  using Clock = std::chrono::steady_clock;
  // What a task hands back to run once its client's slot is free again: the server posts the
  // answer there, so a client that sends its next request the moment it has the answer is never
  // refused because its previous one still counts.
  using Then = std::function<void()>;
  // `run(expired)`: expired is true when the deadline passed before a worker got to it (then
  // run on the watcher thread, so it must only answer, never compute).
  using Task = std::function<Then(bool expired)>;

  struct Options {
    unsigned threads = 1;
    std::size_t max_queue = 256;
    std::size_t max_per_client = 0;  // 0: no cap
  };
  enum class Admission { accepted, queue_full, client_busy, stopping };

  explicit ComputePool(Options options);
  ComputePool(unsigned threads, std::size_t max_queue) : ComputePool(Options{threads, max_queue, 0}) {}
  ~ComputePool();
  ComputePool(const ComputePool&) = delete;
  ComputePool& operator=(const ComputePool&) = delete;

  Admission admit(Task task, Clock::time_point deadline, const std::string& client = {});
  // A task with nothing to run after its slot is freed.
  template <class F>
    requires std::is_void_v<std::invoke_result_t<F&, bool>>
  Admission admit(F task, Clock::time_point deadline, const std::string& client = {}) {
    return admit(Task([task = std::move(task)](bool expired) mutable -> Then {
                   task(expired);
                   return {};
                 }),
                 deadline, client);
  }
  // True when admitted (the task will run, expired or not).
  template <class F>
  bool submit(F&& task, Clock::time_point deadline, const std::string& client = {}) {
    return admit(std::forward<F>(task), deadline, client) == Admission::accepted;
  }
  // Stops taking work, runs what is queued, joins the workers and the watcher.
  void shutdown();

  std::size_t queued() const;
  std::size_t busy() const;
  std::size_t clients() const;  // clients with queued or running tasks
  std::uint64_t expired_in_queue() const;  // tasks the watcher expired (since the start)
  unsigned threads() const { return static_cast<unsigned>(workers_.size()); }
  const Options& options() const { return options_; }

 private:
  struct Item {
    Task task;
    Clock::time_point deadline;
    std::string client;
  };
  struct ClientState {
    std::deque<Item> queued;
    std::size_t running = 0;
  };

  void work();
  void watch();
  bool next_item(Item& out);  // under the lock: the next task round-robin, if any
  void finished(const std::string& client);
  void forget_if_idle(std::map<std::string, ClientState>::iterator it);

  Options options_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;     // workers: a task was queued, or stopping
  std::condition_variable deadlines_; // watcher: the earliest deadline may have changed
  std::map<std::string, ClientState> clients_;
  std::deque<std::string> rotation_;  // clients with queued tasks, in serving order
  std::size_t queued_ = 0;
  std::size_t busy_ = 0;
  std::uint64_t expired_in_queue_ = 0;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
  std::thread watcher_;
};

}  // namespace tourmap::server
