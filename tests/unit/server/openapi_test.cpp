// The contract and the code must agree: every route the server registers is in
// api/openapi.yaml with its method, and every path in the spec is served.

#include "api/openapi.hpp"
#include "server/routes_table.hpp"
#include "server/ws_session.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>

namespace tourmap::server {
namespace {

// (METHOD, path) pairs from the `paths:` section: a path is a 2-space-indented key starting with
// '/', a method a 4-space-indented get/post/put/patch/delete key under it.
std::set<std::pair<std::string, std::string>> spec_operations() {
  std::set<std::pair<std::string, std::string>> ops;
  std::istringstream in{std::string(api::openapi_yaml())};
  std::string line, path;
  bool in_paths = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != ' ') in_paths = line.rfind("paths:", 0) == 0;
    if (!in_paths) continue;
    if (line.rfind("  /", 0) == 0 && line.back() == ':') {
      path = line.substr(2, line.size() - 3);
    } else if (line.rfind("    ", 0) == 0 && line[4] != ' ' && !path.empty()) {
      auto key = line.substr(4, line.find(':') - 4);
      if (key == "get" || key == "post" || key == "put" || key == "patch" || key == "delete") {
        std::transform(key.begin(), key.end(), key.begin(), ::toupper);
        ops.emplace(key, path);
      }
    }
  }
  return ops;
}

TEST(OpenApi, RegisteredRoutesAndSpecAgree) {
  auto spec = spec_operations();
  ASSERT_GT(spec.size(), 5u);
  std::set<std::pair<std::string, std::string>> code;
  for (auto [method, path] : registered_routes())
    code.emplace(method == "WS" ? "GET" : method, path);  // WebSocket endpoints are documented as GET (upgrade)
  for (const auto& op : code) EXPECT_TRUE(spec.count(op)) << op.first << " " << op.second << " is not in openapi.yaml";
  for (const auto& op : spec) EXPECT_TRUE(code.count(op)) << op.first << " " << op.second << " is not registered";
}

// WS /api/v1/events, as openapi.yaml describes it: {"type": "ping"} gets a pong, any other
// message an error message. Found by fuzz_ws_messages (its input first): {"type": 240} made
// the handler throw json::type_error (value("type", "") on a number), and nothing above a
// WebSocket message handler catches, so one message from any client ended the server's I/O
// loop.
TEST(OpenApi, EventsEndpointAnswersEveryMessageWithoutThrowing) {
  Config config = default_config();
  config.access_log = "off";
  config.compute_threads = 1;
  ServerState state(config);
  store::DbPool db(":memory:");
  boost::asio::io_context ioc;
  EventHub events(ioc, db, std::chrono::milliseconds(1000));
  const WsEndpoint ep = events.endpoint();
  auto session = std::make_shared<WsSession>(boost::asio::ip::tcp::socket(ioc), state, ep, "/api/v1/events");
  for (const char* message : {"{\"type\":240}", "{\"type\":\"ack\",\"fn}", "{\x82", "null", "{\"type\":[\"ping\"]}",
                              "{\"type\":{}}", "{\"type\":null}", "{\"type\":\"ping\"}"}) {
    EXPECT_NO_THROW(ep.on_text(session, message)) << message;
    ioc.poll();  // the queued answer (the session is not open, so it is not written)
  }
}

}  // namespace
}  // namespace tourmap::server
