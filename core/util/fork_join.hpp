#pragma once
// A tiny fork-join pool for per-frame work on a fixed number of threads: the calling thread plus
// `threads - 1` persistent workers, created once (not per frame), that help when they can.
//
// Contract of run(fn):
//  - fn(0) runs on the calling thread; each worker that wakes up while fn(0) is still running
//    also calls fn(t) with its own t in [1, threads()). A worker that wakes up later skips the
//    job, so the caller never waits for a worker that has not started (a busy machine may not
//    schedule it in time). fn must therefore share its work through its own queue (e.g. an
//    atomic chunk counter) such that the caller alone finishes it, and be safe to run
//    concurrently for different t.
//  - run returns after every fn call that started has returned; their writes are then visible
//    to the caller.
//  - run is not reentrant and is called from one thread at a time (the pool's owner).
//  - An exception thrown by any fn(t) is rethrown by run (the caller's first, else a worker's),
//    after all started calls have ended.
//  - The destructor stops and joins the workers; it must not race a run.

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace tourmap::util {

class ForkJoin {
 public:
  explicit ForkJoin(int threads) {
    try {
      for (int t = 1; t < threads; ++t) workers_.emplace_back([this, t] { work(t); });
    } catch (...) {  // could not start a thread: join those started, then report
      stop_workers();
      throw;
    }
  }
  ~ForkJoin() { stop_workers(); }
  ForkJoin(const ForkJoin&) = delete;
  ForkJoin& operator=(const ForkJoin&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  void run(const std::function<void(int)>& fn) {
    if (workers_.empty()) {
      fn(0);
      return;
    }
    {
      std::lock_guard lock(mutex_);
      fn_ = &fn;
      open_ = true;
      error_ = nullptr;
      ++generation_;
    }
    start_.notify_all();
    std::exception_ptr mine;
    try {
      fn(0);
    } catch (...) {
      mine = std::current_exception();
    }
    std::unique_lock lock(mutex_);
    open_ = false;  // workers waking from now on skip this job
    done_.wait(lock, [this] { return running_ == 0; });
    fn_ = nullptr;
    if (mine) std::rethrow_exception(mine);
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void stop_workers() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    start_.notify_all();
    for (auto& w : workers_) w.join();
  }

  void work(int t) {
    std::uint64_t seen = 0;
    for (;;) {
      const std::function<void(int)>* fn = nullptr;
      {
        std::unique_lock lock(mutex_);
        start_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
        if (!open_) continue;  // woke too late: the caller has finished this job alone
        fn = fn_;
        ++running_;
      }
      std::exception_ptr error;
      try {
        (*fn)(t);
      } catch (...) {
        error = std::current_exception();
      }
      std::lock_guard lock(mutex_);
      if (error && !error_) error_ = error;
      if (--running_ == 0) done_.notify_one();
    }
  }

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  const std::function<void(int)>* fn_ = nullptr;
  std::uint64_t generation_ = 0;
  int running_ = 0;
  bool open_ = false, stop_ = false;
  std::exception_ptr error_;
};

}  // namespace tourmap::util
