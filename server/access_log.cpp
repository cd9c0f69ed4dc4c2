#include "access_log.hpp"

#include <ctime>
#include <stdexcept>

namespace tourmap::server {

AccessLog::AccessLog(const std::string& target) {
  if (target == "off") return;
  if (target == "-" || target.empty()) {
    out_ = stdout;
    return;
  }
  out_ = std::fopen(target.c_str(), "a");
  if (!out_) throw std::runtime_error("cannot open access log " + target);
  owned_ = true;
}

AccessLog::~AccessLog() {
  if (owned_) std::fclose(out_);
}

void AccessLog::write(const std::string& remote, const std::string& method, const std::string& target, int status,
                      std::size_t bytes, double ms) {
  if (!out_) return;
  std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char when[32];
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &tm);
  // Control characters in the target are escaped so a request cannot forge log lines.
  std::string safe;
  for (char c : target.substr(0, 2048)) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned char>(c));
      safe += buf;
    } else {
      safe += c;
    }
  }
  std::lock_guard lock(mutex_);
  std::fprintf(out_, "%s %s \"%s %s\" %d %zu %.2fms\n", when, remote.c_str(), method.c_str(), safe.c_str(), status,
               bytes, ms);
  std::fflush(out_);
}

}  // namespace tourmap::server
