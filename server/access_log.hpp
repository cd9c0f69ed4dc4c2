#pragma once
// One line per request: time, client, request line, status, bytes, milliseconds.

#include <cstdio>
#include <mutex>
#include <string>

namespace tourmap::server {

class AccessLog {
 public:
  // "-" writes to stdout, "off" writes nothing, anything else appends to that file.
  explicit AccessLog(const std::string& target);
  ~AccessLog();
  AccessLog(const AccessLog&) = delete;
  AccessLog& operator=(const AccessLog&) = delete;

  void write(const std::string& remote, const std::string& method, const std::string& target, int status,
             std::size_t bytes, double ms);

 private:
  std::mutex mutex_;
  std::FILE* out_ = nullptr;
  bool owned_ = false;
};

}  // namespace tourmap::server
