#pragma once
// One computation per key at a time: concurrent requests for the same expensive result (a
// prepared deformation system, a metro layout) wait for the first one instead of repeating it.

#include "util/stop.hpp"

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
  // exception) is shared. `*ran` tells whether this call did the work. A run that was stopped
  // (util::Stopped: its own request's deadline or client) says nothing about the waiters' own
  // requests: they run it again themselves, under their own stop tokens.
  T run(const std::string& key, const std::function<T()>& make, bool* ran = nullptr) {
    for (;;) {
      std::shared_future<T> pending;
      bool mine = false;
      std::promise<T> promise;
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
      if (mine) return run_mine(key, make, promise);
      try {
        return pending.get();
      } catch (const util::Stopped&) {
        util::check_stop();  // this request may have been stopped meanwhile too
      }
    }
  }

 private:
  T run_mine(const std::string& key, const std::function<T()>& make, std::promise<T>& promise) {
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

  void finish(const std::string& key) {
    std::lock_guard lock(mutex_);
    running_.erase(key);
  }
  std::mutex mutex_;
  std::map<std::string, std::shared_future<T>> running_;
};

}  // namespace tourmap::api
