// Server lifecycle: graceful shutdown, connection limits and timeouts.

#include "live_server.hpp"

#include <gtest/gtest.h>

#include <future>
#include <thread>

namespace tourmap::test {
namespace {

TEST(Lifecycle, SigtermFinishesInFlightRequestsAndExitsCleanly) {
  LiveServer live;
  // Start a few larger requests, then ask the server to stop while they run.
  std::vector<std::future<HttpResult>> inflight;
  for (int i = 0; i < 4; ++i)
    inflight.push_back(std::async(std::launch::async, [&] { return live.get("/api/v1/roads/monaco"); }));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  auto stopped = live.server->stop();
  for (auto& f : inflight) {
    try {
      auto r = f.get();
      EXPECT_EQ(r.status, 200);  // answered in full, not cut off
      EXPECT_GT(r.body.size(), 100000u);
    } catch (const std::exception&) {
      // A request that had not reached the server before the listener closed is refused:
      // acceptable, as long as none got a truncated answer.
    }
  }
  EXPECT_EQ(stopped.exit_code, 0) << stopped.output;
  EXPECT_NE(stopped.output.find("shutdown: done"), std::string::npos) << stopped.output;
  // The database is closed cleanly and usable afterwards.
  auto check = run_command({kTourmapBin, "migrate", "--db", live.db()});
  EXPECT_EQ(check.exit_code, 0) << check.output;
}

TEST(Lifecycle, WebSocketConnectionLimitRefusesClearly) {
  LiveServer live({"--max-ws", "1"});
  WsClient first(live.port(), "/api/v1/events");
  first.receive(std::chrono::seconds(5));
  EXPECT_THROW(WsClient(live.port(), "/api/v1/events"), std::exception);
  EXPECT_EQ(live.get("/healthz").status, 200);
}

TEST(Lifecycle, IdleConnectionsAreClosed) {
  LiveServer live({"--idle-timeout", "1"});
  auto start = std::chrono::steady_clock::now();
  // Connect and send nothing: the server closes the connection after the idle timeout.
  auto answer = raw_exchange(live.port(), "", std::chrono::seconds(10));
  auto waited = std::chrono::steady_clock::now() - start;
  EXPECT_TRUE(answer.empty());
  EXPECT_LT(waited, std::chrono::seconds(5));
}

}  // namespace
}  // namespace tourmap::test
