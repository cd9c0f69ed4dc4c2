#pragma once
// A small thread-safe LRU map bounded by total cost (bytes, or 1 per entry). Evicted values
// that a request still holds (shared_ptr) live until it lets go.

#include <functional>
#include <list>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>

namespace tourmap::api {

template <typename Value>
class LruCache {
 public:
  explicit LruCache(std::size_t capacity) : capacity_(capacity) {}

  std::optional<Value> get(const std::string& key) {
    std::lock_guard lock(mutex_);
    auto it = index_.find(key);
    if (it == index_.end()) return std::nullopt;
    order_.splice(order_.begin(), order_, it->second);  // most recent first
    return it->second->value;
  }

  // Inserts or replaces (a replaced entry's cost is updated). An entry dearer than the whole
  // capacity is not kept (never worth evicting everything for), and neither is an older value.
  void put(const std::string& key, Value value, std::size_t cost = 1) {
    std::lock_guard lock(mutex_);
    if (auto it = index_.find(key); it != index_.end()) {
      used_ -= it->second->cost;
      order_.erase(it->second);
      index_.erase(it);
    }
    if (cost > capacity_) return;
    order_.push_front({key, std::move(value), cost});
    index_[key] = order_.begin();
    used_ += cost;
    while (used_ > capacity_ && !order_.empty()) {
      used_ -= order_.back().cost;
      index_.erase(order_.back().key);
      order_.pop_back();
    }
  }

  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return order_.size();
  }
  std::size_t used() const {
    std::lock_guard lock(mutex_);
    return used_;
  }

 private:
  struct Entry {
    std::string key;
    Value value;
    std::size_t cost;
  };
  mutable std::mutex mutex_;
  std::list<Entry> order_;
  std::unordered_map<std::string, typename std::list<Entry>::iterator> index_;
  std::size_t capacity_;
  std::size_t used_ = 0;
};

}  // namespace tourmap::api
