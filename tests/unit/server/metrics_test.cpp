#include "server/metrics.hpp"

#include <gtest/gtest.h>

namespace tourmap::server {
namespace {

TEST(Metrics, PrometheusTextFormat) {
  Metrics m;
  m.observe("/api/v1/cities/{id}", "GET", 200, 0.003);
  m.observe("/api/v1/cities/{id}", "GET", 200, 0.2);
  m.observe("/api/v1/cities/{id}", "GET", 404, 0.0001);
  m.add_gauge("tourmap_test_gauge", "A gauge.", [] { return 7.0; });
  auto text = m.render();
  EXPECT_NE(text.find("# TYPE tourmap_http_requests_total counter"), std::string::npos);
  EXPECT_NE(text.find("tourmap_http_requests_total{route=\"/api/v1/cities/{id}\",method=\"GET\",status=\"200\"} 2"),
            std::string::npos);
  EXPECT_NE(text.find("tourmap_http_request_duration_seconds_bucket{route=\"/api/v1/cities/{id}\",le=\"0.005\"} 2"),
            std::string::npos);
  EXPECT_NE(text.find("tourmap_http_request_duration_seconds_bucket{route=\"/api/v1/cities/{id}\",le=\"+Inf\"} 3"),
            std::string::npos);
  EXPECT_NE(text.find("tourmap_http_request_duration_seconds_count{route=\"/api/v1/cities/{id}\"} 3"),
            std::string::npos);
  EXPECT_NE(text.find("tourmap_test_gauge 7"), std::string::npos);
}

}  // namespace
}  // namespace tourmap::server
