#pragma once
// Request metrics in the Prometheus text format: per route (the route pattern, so ids do not
// explode the label space), method and status, a counter and a latency histogram. Every label
// comes from a closed set: routes are patterns or fixed names, methods outside the standard
// ones count as "other", statuses are three-digit codes.

#include <array>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <tuple>

namespace tourmap::server {

class Metrics {
 public:
  static constexpr std::array<double, 14> kBuckets = {0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05,
                                                      0.1,    0.25,  0.5,    1.0,   2.5,   5.0,  10.0};

  void observe(const std::string& route, const std::string& method, int status, double seconds);
  // Gauges are read at scrape time.
  void add_gauge(std::string name, std::string help, std::function<double()> read);

  std::string render() const;

 private:
  struct Histogram {
    std::array<unsigned long long, kBuckets.size()> buckets{};
    unsigned long long count = 0;
    double sum = 0.0;
  };
  struct Gauge {
    std::string help;
    std::function<double()> read;
  };
  mutable std::mutex mutex_;
  std::map<std::tuple<std::string, std::string, int>, unsigned long long> requests_;
  std::map<std::string, Histogram> latency_;
  std::map<std::string, Gauge> gauges_;
};

}  // namespace tourmap::server
