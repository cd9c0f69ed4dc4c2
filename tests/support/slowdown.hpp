#pragma once
// How much slower the code under test runs in this build: time and memory bounds in tests are
// multiplied by it. ASan+UBSan builds (TOURMAP_SANITIZE, scripts/test-sanitizers) run 5-20x
// slower and hold freed memory in a quarantine; release builds are the measure.

namespace tourmap::test {

#if defined(TOURMAP_SANITIZED)
inline constexpr double kSlowdown = 10.0;
#else
inline constexpr double kSlowdown = 1.0;
#endif

}  // namespace tourmap::test
