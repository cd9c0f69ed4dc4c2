#include "metrics.hpp"

#include <cstdio>
#include <sstream>

namespace tourmap::server {
namespace {

// Label values escape backslash, quote and newline (Prometheus text format 0.0.4).
std::string label(const std::string& v) {
  std::string out;
  for (char c : v) {
    if (c == '\\' || c == '"') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out;
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// Methods from a closed set: a client can send any token as a method, and every new label value
// would be a new series kept for the life of the process.
const std::string& method_label(const std::string& method) {
  static const std::string kKnown[] = {"GET", "HEAD", "POST", "PUT", "DELETE", "OPTIONS", "PATCH", "-"};
  static const std::string kOther = "other";
  for (const auto& m : kKnown)
    if (m == method) return m;
  return kOther;
}

}  // namespace

void Metrics::observe(const std::string& route, const std::string& method, int status, double seconds) {
  if (status < 100 || status > 599) status = 0;  // a closed set too
  std::lock_guard lock(mutex_);
  ++requests_[{route, method_label(method), status}];
  auto& h = latency_[route];
  for (std::size_t i = 0; i < kBuckets.size(); ++i)
    if (seconds <= kBuckets[i]) ++h.buckets[i];
  ++h.count;
  h.sum += seconds;
}

void Metrics::add_gauge(std::string name, std::string help, std::function<double()> read) {
  std::lock_guard lock(mutex_);
  gauges_[std::move(name)] = {std::move(help), std::move(read)};
}

std::string Metrics::render() const {
  std::ostringstream out;
  std::lock_guard lock(mutex_);
  out << "# HELP tourmap_http_requests_total HTTP requests by route pattern, method and status.\n"
         "# TYPE tourmap_http_requests_total counter\n";
  for (const auto& [key, count] : requests_) {
    const auto& [route, method, status] = key;
    out << "tourmap_http_requests_total{route=\"" << label(route) << "\",method=\"" << label(method)
        << "\",status=\"" << status << "\"} " << count << "\n";
  }
  out << "# HELP tourmap_http_request_duration_seconds Time from request read to response ready to write.\n"
         "# TYPE tourmap_http_request_duration_seconds histogram\n";
  for (const auto& [route, h] : latency_) {
    auto l = label(route);
    for (std::size_t i = 0; i < kBuckets.size(); ++i)
      out << "tourmap_http_request_duration_seconds_bucket{route=\"" << l << "\",le=\"" << number(kBuckets[i])
          << "\"} " << h.buckets[i] << "\n";
    out << "tourmap_http_request_duration_seconds_bucket{route=\"" << l << "\",le=\"+Inf\"} " << h.count << "\n";
    out << "tourmap_http_request_duration_seconds_sum{route=\"" << l << "\"} " << number(h.sum) << "\n";
    out << "tourmap_http_request_duration_seconds_count{route=\"" << l << "\"} " << h.count << "\n";
  }
  for (const auto& [name, g] : gauges_) {
    out << "# HELP " << name << " " << g.help << "\n# TYPE " << name << " gauge\n";
    out << name << " " << number(g.read()) << "\n";
  }
  return out.str();
}

}  // namespace tourmap::server
