// Hostile and malformed requests: each gets a clear 4xx naming the field, and the server keeps
// serving afterwards.

#include "live_server_suite.hpp"

#include <gtest/gtest.h>

namespace tourmap::test {
namespace {

class BadInput : public LiveServerSuite<BadInput> {
 public:
  static std::vector<std::string> server_flags() { return {"--max-body", "65536", "--max-header", "8192"}; }

 protected:
  void TearDown() override { EXPECT_EQ(live->get("/healthz").status, 200) << "server stopped serving"; }

  static HttpResult post_json(const std::string& target, const std::string& body) {
    return http_request(live->port(), "POST", target, {{"Content-Type", "application/json"}}, body);
  }
};

TEST_F(BadInput, UnknownIds) {
  expect_error(live->get("/api/v1/cities/atlantis"), 404, "id");
  expect_error(live->get("/api/v1/cities/atlantis/metro"), 404, "id");
  expect_error(live->get("/api/v1/cities/ATLANTIS/pois"), 404, "id");
  expect_error(live->get("/api/v1/roads/nowhere"), 404, "id");
  expect_error(live->get("/api/v1/nothing-here"), 404, "path");
}

TEST_F(BadInput, BadBBoxes) {
  for (std::string bbox : {"16.4,48.1,16.3,48.3", "16.3,48.3,16.4,48.1", "nan,48.1,16.4,48.3", "16.3,inf,16.4,48.3",
                           "1,2,3", "a,b,c,d", "1e999,0,1,1", "-200,0,0,1", "1,2,3,4,5", "%20"})
    expect_error(live->get("/api/v1/cities/vienna/pois?bbox=" + bbox), 400, "bbox");
  expect_error(live->get("/api/v1/roads/monaco?bbox=1,1,0,0"), 400, "bbox");
  expect_error(live->get("/api/v1/cities/vienna/metro?bbox=1,1,0,0"), 400, "bbox");
}

TEST_F(BadInput, WrongTypesInQueries) {
  expect_error(live->get("/api/v1/cities/vienna/pois?limit=ten"), 400, "limit");
  expect_error(live->get("/api/v1/cities/vienna/pois?limit=0"), 400, "limit");
  expect_error(live->get("/api/v1/cities/vienna/pois?limit=100001"), 400, "limit");
  expect_error(live->get("/api/v1/cities/vienna/pois?offset=-3"), 400, "offset");
  expect_error(live->get("/api/v1/roads/monaco?nodes=perhaps"), 400, "nodes");
}

TEST_F(BadInput, MalformedJsonAndGeoJsonBodies) {
  const std::string target = "/api/v1/cities/vienna/pois/query";
  expect_error(post_json(target, "{\"within\": "), 400, "body");
  expect_error(post_json(target, "not json at all"), 400, "body");
  expect_error(post_json(target, "[1,2,3]"), 400, "body");
  expect_error(post_json(target, std::string(1000, '[')), 400, "body");
  expect_error(post_json(target, R"({"limit": "5"})"), 400, "limit");
  expect_error(post_json(target, R"({"limit": 2.5})"), 400, "limit");
  expect_error(post_json(target, R"({"bbox": [1, 2, 3]})"), 400, "bbox");
  expect_error(post_json(target, R"({"categories": [1]})"), 400, "categories[0]");
  expect_error(post_json(target, R"({"within": {"type": "Point", "coordinates": [16, 48]}})"), 400, "within.type");
  expect_error(post_json(target, R"({"within": {"type": "Polygon", "coordinates": [[[0,0],[1,1],[1,0],[0,1],[0,0]]]}})"),
               400, "within.coordinates[0]");  // self-intersecting
  expect_error(post_json(target, R"({"within": {"type": "Polygon", "coordinates": [[[0,0],[1,0],[2,0],[0,0]]]}})"), 400,
               "within.coordinates[0]");  // zero area
  expect_error(post_json(target, R"({"within": {"type": "Polygon", "coordinates": [[[0,0],[1,0],[1,1],[0,0.5]]]}})"), 400,
               "within.coordinates[0]");  // not closed
  expect_error(post_json(target, R"({"within": {"type": "Polygon", "coordinates": [[[0,0],["1",0],[1,1],[0,0]]]}})"),
               400, "within.coordinates[0][1]");
  auto wrong_type = http_request(live->port(), "POST", target, {{"Content-Type", "text/plain"}}, "{}");
  expect_error(wrong_type, 415, "Content-Type");
}

TEST_F(BadInput, WrongMethodAndTarget) {
  auto r = http_request(live->port(), "DELETE", "/api/v1/cities/vienna/pois/query");
  expect_error(r, 405, "method");
  EXPECT_EQ(r.header("allow"), "POST");
  expect_error(live->get("/api/v1/cities/vi%zzenna"), 400, "path");
  expect_error(live->get("/api/v1/cities/vienna%00/pois"), 400, "path");
}

TEST_F(BadInput, OversizedBodyIs413) {
  std::string big(70000, ' ');
  auto r = post_json("/api/v1/cities/vienna/pois/query", "{" + big + "}");
  EXPECT_EQ(r.status, 413);
  EXPECT_EQ(error_of(r)["code"], "payload_too_large");
}

TEST_F(BadInput, OversizedHeaderIs431) {
  auto r = live->get("/healthz", {{"X-Big", std::string(10000, 'a')}});
  EXPECT_EQ(r.status, 431);
}

TEST_F(BadInput, GarbageOnTheWireIs400) {
  auto answer = raw_exchange(live->port(), "THIS IS NOT HTTP\r\n\r\n", std::chrono::seconds(5));
  EXPECT_EQ(answer.rfind("HTTP/1.1 400", 0), 0u) << answer;
  auto nothing = raw_exchange(live->port(), "GET / HTTP/1.1\r\nHost: x\r\nContent-Length: -5\r\n\r\n",
                              std::chrono::seconds(5));
  EXPECT_EQ(nothing.rfind("HTTP/1.1 400", 0), 0u) << nothing;
}

TEST_F(BadInput, UnknownWebSocketPath) {
  EXPECT_THROW(WsClient(live->port(), "/api/v1/nope"), std::exception);
}

}  // namespace
}  // namespace tourmap::test
