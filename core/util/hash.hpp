#pragma once
// FNV-1a 64: a fast, stable (across builds and runs) hash for cache keys, ETags and source
// fingerprints. Not for security.

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace tourmap::util {

inline constexpr std::uint64_t kFnvOffset = 1469598103934665603ull;

// Continues a hash `h` over `bytes` (start with kFnvOffset).
inline std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t h = kFnvOffset) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

inline std::string hex64(std::uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace tourmap::util
