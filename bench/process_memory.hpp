#pragma once
// Resident memory of this process, for the benchmarks' peak-memory columns (Linux).

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace tourmap::bench {

// VmHWM (peak) or VmRSS (now) from /proc/self/status, in MB; 0 when unreadable.
inline double status_mb(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return std::strtod(line.c_str() + std::strlen(key), nullptr) / 1024.0;
  return 0;
}

// Resets VmHWM to the current RSS (Linux 4.0+), so the next peak is one step's; false when the
// kernel refuses.
inline bool reset_peak() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return static_cast<bool>(out);
}

}  // namespace tourmap::bench
