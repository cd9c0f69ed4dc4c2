#include "compute_pool.hpp"

namespace tourmap::server {

ComputePool::ComputePool(unsigned threads, std::size_t max_queue) : max_queue_(max_queue) {
  if (threads == 0) threads = 1;
  for (unsigned i = 0; i < threads; ++i) workers_.emplace_back([this] { work(); });
}

ComputePool::~ComputePool() { shutdown(); }

bool ComputePool::submit(Task task, Clock::time_point deadline) {
  {
    std::lock_guard lock(mutex_);
    if (stopping_ || queue_.size() >= max_queue_) return false;
    queue_.push_back({std::move(task), deadline});
  }
  ready_.notify_one();
  return true;
}

void ComputePool::shutdown() {
  {
    std::lock_guard lock(mutex_);
    if (stopping_ && workers_.empty()) return;
    stopping_ = true;
  }
  ready_.notify_all();
  for (auto& t : workers_)
    if (t.joinable()) t.join();
  workers_.clear();
}

std::size_t ComputePool::queued() const {
  std::lock_guard lock(mutex_);
  return queue_.size();
}

std::size_t ComputePool::busy() const {
  std::lock_guard lock(mutex_);
  return busy_;
}

void ComputePool::work() {
  while (true) {
    Item item;
    {
      std::unique_lock lock(mutex_);
      ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping and drained
      item = std::move(queue_.front());
      queue_.pop_front();
      ++busy_;
    }
    item.task(Clock::now() > item.deadline);
    std::lock_guard lock(mutex_);
    --busy_;
  }
}

}  // namespace tourmap::server
