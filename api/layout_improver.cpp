#include "layout_improver.hpp"

#include "util/stop.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <system_error>

namespace tourmap::api {

LayoutImprover::Admission LayoutImprover::push(const std::string& key, Job job) {
  {
    std::lock_guard lock(mutex_);
    if (stop_) return Admission::refused;
    if (running_ == key) return Admission::pending;
    if (std::any_of(queue_.begin(), queue_.end(), [&](const auto& queued) { return queued.first == key; }))
      return Admission::pending;
    if (queue_.size() >= max_queue_) {  // the oldest waits longest: newer requests are what is looked at now
      queue_.pop_front();
      ++dropped_;
    }
    queue_.emplace_back(key, std::move(job));
    if (!thread_.joinable()) {
      try {
        thread_ = std::thread([this] { work(); });
      } catch (const std::system_error&) {  // no thread to be had: nothing runs, the answer says so
        queue_.pop_back();
        return Admission::refused;
      }
    }
  }
  wake_.notify_one();
  return Admission::queued;
}

void LayoutImprover::request_stop() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
    queue_.clear();
  }
  wake_.notify_all();
}

void LayoutImprover::stop() {
  request_stop();
  std::thread worker;
  {
    std::lock_guard lock(mutex_);
    worker = std::move(thread_);
  }
  if (worker.joinable()) worker.join();
}

LayoutImprover::Stats LayoutImprover::stats() const {
  std::lock_guard lock(mutex_);
  return {queue_.size(), running_.empty() ? 0u : 1u, dropped_, failed_};
}

void LayoutImprover::work() {
  // Below the request threads: on 2 cores a background MIP must not slow foreground answers.
  // Linux keeps nice values per thread, and the CBC child spawned from here inherits it. A
  // failure leaves the thread at the normal priority, which is still one core at most.
  (void)setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), 10);
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (stop_) return;
    auto [key, job] = std::move(queue_.front());
    queue_.pop_front();
    running_ = key;
    lock.unlock();
    bool failed = false;
    try {
      job(stop_);
    } catch (const util::Stopped&) {  // shutdown (or the job's own deadline): nothing to keep
    } catch (const std::exception& e) {
      std::fprintf(stderr, "layout improvement %s failed: %s\n", key.c_str(), e.what());
      failed = true;
    } catch (...) {
      std::fprintf(stderr, "layout improvement %s failed\n", key.c_str());
      failed = true;
    }
    job = nullptr;  // its captures (a city's data) go now, not when the next job comes
    lock.lock();
    running_.clear();
    if (failed) ++failed_;
  }
}

}  // namespace tourmap::api
