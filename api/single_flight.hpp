#pragma once
// One computation per key at a time: concurrent requests for the same expensive result (a
// prepared deformation system, a metro layout) wait for the first one instead of repeating it.

#include <functional>
#include <future>
#include <map>
#include <mutex>
#include <string>

namespace tourmap::api {

template <typename T>
class SingleFlight {
 public:
  // Runs `make` unless a call for `key` is already running, in which case its result (or
  // exception) is shared. `*ran` tells whether this call did the work.
  T run(const std::string& key, const std::function<T()>& make, bool* ran = nullptr) {
    std::shared_future<T> pending;
    std::promise<T> promise;
    bool mine = false;
    {
      std::lock_guard lock(mutex_);
      auto it = running_.find(key);
      if (it != running_.end()) {
        pending = it->second;
      } else {
        pending = promise.get_future().share();
        running_.emplace(key, pending);
        mine = true;
      }
    }
    if (ran) *ran = mine;
    if (!mine) return pending.get();
    try {
      T value = make();
      promise.set_value(value);
      finish(key);
      return value;
    } catch (...) {
      promise.set_exception(std::current_exception());
      finish(key);
      throw;
    }
  }

 private:
  void finish(const std::string& key) {
    std::lock_guard lock(mutex_);
    running_.erase(key);
  }
  std::mutex mutex_;
  std::map<std::string, std::shared_future<T>> running_;
};

}  // namespace tourmap::api
