#pragma once
// Growing large buffers with their pages faulted in by one kernel call. A first write to a fresh
// 4 KiB page traps into the kernel; on the virtual machines tourmap runs on, that trap costs
// ~12 us (measured: 256 MiB of fresh std::vector took 800 ms to zero, while
// madvise(MADV_POPULATE_WRITE) faulted the same in 68 ms). Algorithms that build 10^8-byte
// arrays (a cluster tree over 10^6 POIs) spent a third of their time in those traps.

#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tourmap::util {

// Faults in the whole pages inside [p, p + bytes) for writing; a no-op where the kernel cannot
// (older than Linux 5.14, other systems): the pages then fault one by one as before.
inline void prefault(void* p, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  constexpr std::uintptr_t kPage = 4096;
  constexpr std::size_t kWorthIt = 1 << 20;  // below 1 MiB the call is not worth it
  if (bytes < kWorthIt) return;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(p) + kPage - 1) & ~(kPage - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(kPage - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#else
  (void)p;
  (void)bytes;
#endif
}

// v.reserve(n), with the new capacity faulted in when it had to grow.
template <class T>
void reserve_prefaulted(std::vector<T>& v, std::size_t n) {
  if (v.capacity() >= n) return;
  v.reserve(n);
  prefault(v.data(), v.capacity() * sizeof(T));
}

// v.assign(n, value) / v.resize(n) through reserve_prefaulted.
template <class T>
void assign_prefaulted(std::vector<T>& v, std::size_t n, const T& value) {
  reserve_prefaulted(v, n);
  v.assign(n, value);
}
template <class T>
void resize_prefaulted(std::vector<T>& v, std::size_t n) {
  reserve_prefaulted(v, n);
  v.resize(n);
}

}  // namespace tourmap::util
