#pragma once
// Wall time since a start point, in milliseconds: the timings that stats and responses report.

#include <chrono>

namespace tourmap::util {

using Clock = std::chrono::steady_clock;

inline double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace tourmap::util
