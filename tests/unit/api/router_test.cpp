#include "api/router.hpp"

#include <gtest/gtest.h>

namespace tourmap::api {
namespace {

Response ok(Request&) { return json_response({{"ok", true}}); }

TEST(Router, MatchesLiteralsAndParameters) {
  Router router;
  router.add("GET", "/api/v1/cities", Exec::heavy, ok);
  router.add("GET", "/api/v1/cities/{id}/metro", Exec::heavy, ok);
  router.add("POST", "/api/v1/cities/{id}/pois/query", Exec::heavy, ok);

  Request req;
  req.method = "GET";
  req.path = "/api/v1/cities/vienna/metro";
  auto m = router.match(req);
  ASSERT_NE(m.route, nullptr);
  EXPECT_EQ(m.route->pattern, "/api/v1/cities/{id}/metro");
  EXPECT_EQ(req.param("id"), "vienna");

  req.path = "/api/v1/cities/";  // trailing slash is the same path
  EXPECT_NE(router.match(req).route, nullptr);
  req.path = "/api/v1/cities/vienna/metro/extra";
  EXPECT_EQ(router.match(req).route, nullptr);
}

TEST(Router, ReportsAllowedMethods) {
  Router router;
  router.add("POST", "/api/v1/cities/{id}/pois/query", Exec::heavy, ok);
  Request req;
  req.method = "GET";
  req.path = "/api/v1/cities/x/pois/query";
  auto m = router.match(req);
  EXPECT_EQ(m.route, nullptr);
  EXPECT_EQ(m.allowed, std::vector<std::string>{"POST"});
}

TEST(Router, HeadUsesTheGetRoute) {
  Router router;
  router.add("GET", "/healthz", Exec::io, ok);
  Request req;
  req.method = "HEAD";
  req.path = "/healthz";
  EXPECT_NE(router.match(req).route, nullptr);
}

TEST(Router, SplitPath) {
  EXPECT_EQ(split_path("/a//b/"), (std::vector<std::string>{"a", "b"}));
  EXPECT_TRUE(split_path("/").empty());
}

}  // namespace
}  // namespace tourmap::api
