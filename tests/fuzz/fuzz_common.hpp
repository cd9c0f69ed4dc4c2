#pragma once
// Helpers shared by the libFuzzer targets: the input as a string, and one scratch directory per
// process for the loaders that take a file path (each target rewrites the same file name on
// every run, so a long run does not fill the disk).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

// A property the code under test promises; a violation is a finding (abort, so libFuzzer
// keeps the input as a crash).
#define FUZZ_CHECK(cond)                                                                     \
  do {                                                                                       \
    if (!(cond)) {                                                                           \
      std::fprintf(stderr, "FUZZ_CHECK failed: %s (%s:%d)\n", #cond, __FILE__, __LINE__); \
      std::abort();                                                                          \
    }                                                                                        \
  } while (0)

namespace tourmap::fuzz {

inline std::string_view as_view(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// A directory of its own, created on first use and removed at exit.
class ScratchDir {
 public:
  static ScratchDir& get() {
    static ScratchDir dir;
    return dir;
  }
  const std::filesystem::path& path() const { return path_; }
  // Writes `content` to `name` (truncating) and returns the full path.
  std::string write(const std::string& name, std::string_view content) const {
    auto full = path_ / name;
    for (int attempt = 0;; ++attempt) {
      std::ofstream out(full, std::ios::binary | std::ios::trunc);
      out.write(content.data(), static_cast<std::streamsize>(content.size()));
      out.close();
      if (out) return full.string();
      // Someone cleaning the temp directory may have removed ours: make it again, once.
      std::error_code ec;
      if (attempt > 0 || !std::filesystem::create_directories(full.parent_path(), ec))
        throw std::runtime_error("fuzz harness: cannot write " + full.string());
    }
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }

 private:
  // $TMPDIR if set, else /dev/shm when writable, else /tmp. Memory matters: the loaders'
  // targets rewrite a file on every run, and ext4 flushes a truncated-and-rewritten file on
  // close (auto_da_alloc), which made a disk-backed /tmp ten times slower than the parsing.
  static std::string base() {
    if (const char* tmp = std::getenv("TMPDIR"); tmp && *tmp) return tmp;
    if (access("/dev/shm", W_OK | X_OK) == 0) return "/dev/shm";
    return "/tmp";
  }
  ScratchDir() {
    std::string pattern = base() + "/tourmap-fuzz-XXXXXX";
    if (!mkdtemp(pattern.data())) throw std::runtime_error("fuzz harness: mkdtemp failed");
    path_ = pattern;
  }
  std::filesystem::path path_;
};

// Open file descriptors of this process (Linux: /proc/self/fd), to catch loaders that leak one.
inline std::size_t open_fds() {
  std::size_t n = 0;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator("/proc/self/fd", ec); !ec && it != std::filesystem::directory_iterator();
       it.increment(ec))
    ++n;
  return n;
}

// Splits `text` at every occurrence of `sep` (at most `max_parts` parts; the last takes the rest).
inline std::vector<std::string_view> split(std::string_view text, std::string_view sep, std::size_t max_parts) {
  std::vector<std::string_view> parts;
  while (parts.size() + 1 < max_parts) {
    auto at = text.find(sep);
    if (at == std::string_view::npos) break;
    parts.push_back(text.substr(0, at));
    text.remove_prefix(at + sep.size());
  }
  parts.push_back(text);
  return parts;
}

}  // namespace tourmap::fuzz
