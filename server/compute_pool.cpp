#include "compute_pool.hpp"

#include <algorithm>

namespace tourmap::server {

ComputePool::ComputePool(Options options) : options_(options) {
  const unsigned threads = std::max(1u, options_.threads);
  for (unsigned i = 0; i < threads; ++i) workers_.emplace_back([this] { work(); });
  watcher_ = std::thread([this] { watch(); });
}

ComputePool::~ComputePool() { shutdown(); }

ComputePool::Admission ComputePool::admit(Task task, Clock::time_point deadline, const std::string& client) {
  {
    std::lock_guard lock(mutex_);
    if (stopping_) return Admission::stopping;
    if (queued_ >= options_.max_queue) return Admission::queue_full;
    auto& state = clients_[client];
    if (options_.max_per_client > 0 && state.queued.size() + state.running >= options_.max_per_client) {
      forget_if_idle(clients_.find(client));
      return Admission::client_busy;
    }
    if (state.queued.empty()) rotation_.push_back(client);
    state.queued.push_back({std::move(task), deadline, client});
    ++queued_;
  }
  ready_.notify_one();
  deadlines_.notify_one();
  return Admission::accepted;
}

void ComputePool::shutdown() {
  {
    std::lock_guard lock(mutex_);
    if (stopping_ && workers_.empty()) return;
    stopping_ = true;
  }
  ready_.notify_all();
  deadlines_.notify_all();
  for (auto& t : workers_)
    if (t.joinable()) t.join();
  workers_.clear();
  deadlines_.notify_all();  // the workers drained the queue: the watcher has nothing left to wait for
  if (watcher_.joinable()) watcher_.join();
}

std::size_t ComputePool::queued() const {
  std::lock_guard lock(mutex_);
  return queued_;
}

std::size_t ComputePool::busy() const {
  std::lock_guard lock(mutex_);
  return busy_;
}

std::size_t ComputePool::clients() const {
  std::lock_guard lock(mutex_);
  return clients_.size();
}

std::uint64_t ComputePool::expired_in_queue() const {
  std::lock_guard lock(mutex_);
  return expired_in_queue_;
}

void ComputePool::forget_if_idle(std::map<std::string, ClientState>::iterator it) {
  if (it != clients_.end() && it->second.queued.empty() && it->second.running == 0) clients_.erase(it);
}

bool ComputePool::next_item(Item& out) {
  while (!rotation_.empty()) {
    const std::string client = std::move(rotation_.front());
    rotation_.pop_front();
    auto it = clients_.find(client);
    if (it == clients_.end() || it->second.queued.empty()) continue;  // its tasks expired meanwhile
    out = std::move(it->second.queued.front());
    it->second.queued.pop_front();
    --queued_;
    ++it->second.running;
    if (!it->second.queued.empty()) rotation_.push_back(client);
    return true;
  }
  return false;
}

void ComputePool::finished(const std::string& client) {
  std::lock_guard lock(mutex_);
  --busy_;
  auto it = clients_.find(client);
  if (it == clients_.end()) return;
  --it->second.running;
  forget_if_idle(it);
}

void ComputePool::work() {
  while (true) {
    Item item;
    {
      std::unique_lock lock(mutex_);
      ready_.wait(lock, [this] { return stopping_ || queued_ > 0; });
      if (!next_item(item)) {
        if (stopping_) return;  // stopping and drained
        continue;
      }
      ++busy_;
    }
    const Then then = item.task(Clock::now() > item.deadline);
    finished(item.client);
    if (then) then();
  }
}

// Expires queued tasks whose deadline passed: they are answered now, not when a worker frees.
void ComputePool::watch() {
  std::unique_lock lock(mutex_);
  while (true) {
    if (stopping_ && queued_ == 0) return;  // drained: the workers finish what runs
    auto earliest = Clock::time_point::max();
    for (const auto& [client, state] : clients_)
      for (const auto& item : state.queued) earliest = std::min(earliest, item.deadline);
    if (earliest == Clock::time_point::max()) {
      deadlines_.wait(lock);
      continue;
    }
    if (Clock::now() < earliest) {
      deadlines_.wait_until(lock, earliest);
      continue;
    }
    std::vector<Item> expired;
    const auto now = Clock::now();
    for (auto it = clients_.begin(); it != clients_.end();) {
      auto& q = it->second.queued;
      for (auto item = q.begin(); item != q.end();) {
        if (item->deadline <= now) {
          expired.push_back(std::move(*item));
          item = q.erase(item);
          --queued_;
        } else {
          ++item;
        }
      }
      auto next = std::next(it);
      if (q.empty()) std::erase(rotation_, it->first);
      forget_if_idle(it);
      it = next;
    }
    expired_in_queue_ += expired.size();
    lock.unlock();
    for (auto& item : expired)
      if (const Then then = item.task(true)) then();
    lock.lock();
  }
}

}  // namespace tourmap::server
