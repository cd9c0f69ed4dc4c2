#pragma once
// The CPU time this thread has used, as a std::chrono clock. A search with a budget of this
// clock does the same work, and so gives the same result, however busy the machine is (a wall
// clock budget gives less work, and another answer, under load).

#include <chrono>
#include <ctime>

namespace tourmap::util {

struct ThreadCpuClock {
  using duration = std::chrono::nanoseconds;
  using rep = duration::rep;
  using period = duration::period;
  using time_point = std::chrono::time_point<ThreadCpuClock>;
  static constexpr bool is_steady = true;

  static time_point now() noexcept {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return time_point(duration(static_cast<rep>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec));
  }
};

}  // namespace tourmap::util
