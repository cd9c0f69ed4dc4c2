// WebSocket text messages, through the real endpoints the server registers: the crowd stream
// (server::CrowdStreamer::endpoint(): JSON parse, ack/flow control, api::apply_view_message)
// and the catalog events (server::EventHub::endpoint(): ping). Each input is one connection:
// on_open, then every line of the input as one message (at most 32), then on_close, with the
// session's queued sends drained in between. The streamer is never started (no render thread,
// no GL): only the message handling runs.
//
// First byte: bit 0 picks the endpoint. Clean outcome: anything the handlers answer. An
// exception escaping on_text is a finding: WsSession::on_read does not catch, so in the
// server it would leave the I/O thread's run loop.

#include "fuzz_common.hpp"

#include "server/crowd_stream.hpp"
#include "server/events.hpp"
#include "server/ws_session.hpp"
#include "store/migrate.hpp"

#include <memory>

namespace {

using namespace tourmap;

struct World {
  fuzz::ScratchDir& dir = fuzz::ScratchDir::get();
  store::DbPool pool{(dir.path() / "ws.db").string()};
  server::Config config = [] {
    server::Config c;
    c.access_log = "off";
    c.compute_threads = 1;
    return c;
  }();
  server::ServerState state{config};
  boost::asio::io_context ioc;
  server::EventHub events{ioc, pool, std::chrono::milliseconds(1000)};
  api::CrowdAssets assets{(dir.path() / "models").string(), nullptr};
  server::CrowdStreamer crowd{assets, api::CrowdLimits{}};
  server::WsEndpoint crowd_ep = crowd.endpoint();
  server::WsEndpoint events_ep = events.endpoint();

  World() {
    auto db = pool.acquire();
    store::migrate(*db);
  }
};

World& world() {
  static World w;
  return w;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  world();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  World& w = world();
  const bool crowd = (data[0] & 1) == 0;
  const server::WsEndpoint& ep = crowd ? w.crowd_ep : w.events_ep;
  auto session = std::make_shared<server::WsSession>(boost::asio::ip::tcp::socket(w.ioc), w.state, ep,
                                                     crowd ? "/api/v1/crowd/stream" : "/api/v1/events");
  if (ep.on_open) ep.on_open(session);
  w.ioc.poll();
  for (auto message : fuzz::split(fuzz::as_view(data + 1, size - 1), "\n", 32)) {
    ep.on_text(session, std::string(message));
    w.ioc.poll();
  }
  if (ep.on_close) ep.on_close(session);
  w.ioc.poll();
  w.ioc.restart();
  return 0;
}
