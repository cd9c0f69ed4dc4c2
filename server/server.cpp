#include "server.hpp"

#include "events.hpp"
#include "http_session.hpp"
#include "routes_table.hpp"
#include "server_state.hpp"
#include "ws_session.hpp"

#include "store/api_keys.hpp"
#include "store/migrate.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>

#include <cstdio>
#include <thread>

#ifndef TOURMAP_VERSION
#define TOURMAP_VERSION "dev"
#endif

namespace tourmap::server {

namespace net = boost::asio;
using tcp = net::ip::tcp;

namespace {

void add_gauges(ServerState& state) {
  state.metrics.add_gauge("tourmap_http_in_flight", "Requests read and not yet answered.",
                          [&state] { return static_cast<double>(state.in_flight.load()); });
  state.metrics.add_gauge("tourmap_http_connections", "Open HTTP connections.",
                          [&state] { return static_cast<double>(state.http_sessions.size()); });
  state.metrics.add_gauge("tourmap_ws_connections", "Open WebSocket connections.",
                          [&state] { return static_cast<double>(state.ws_sessions.size()); });
  state.metrics.add_gauge("tourmap_compute_queued", "Requests waiting for a compute thread.",
                          [&state] { return static_cast<double>(state.pool.queued()); });
  state.metrics.add_gauge("tourmap_compute_busy", "Compute threads running a request.",
                          [&state] { return static_cast<double>(state.pool.busy()); });
  state.metrics.add_gauge("tourmap_rate_limit_clients",
                          "Client addresses the rate limiter tracks (requests refused: status 429, route rate_limited).",
                          [&state] {
                            state.rate_limiter.evict_idle(std::chrono::steady_clock::now());
                            return static_cast<double>(state.rate_limiter.tracked());
                          });
}

void accept_loop(tcp::acceptor& acceptor, net::io_context& ioc, ServerState& state) {
  acceptor.async_accept(net::make_strand(ioc), [&](boost::system::error_code ec, tcp::socket socket) {
    if (ec == net::error::operation_aborted || !acceptor.is_open()) return;
    if (!ec) std::make_shared<HttpSession>(std::move(socket), state)->run();
    accept_loop(acceptor, ioc, state);
  });
}

}  // namespace

int serve(const Config& config, const std::function<void(unsigned short)>& on_listening) {
  store::DbPool db(config.db_path);
  {
    auto conn = db.acquire();
    for (const auto& name : store::migrate(*conn)) std::printf("migrated: %s\n", name.c_str());
  }
  api::Catalog catalog(db);
  ServerState state(config);  // declared before the io_context: sessions refer to it until the end
  api::DeformService deform(catalog);
  api::MetroService metro(catalog, api::child_process_mip_solver("/proc/self/exe"));
  api::AppContext ctx{db, catalog, deform, metro, TOURMAP_VERSION};
  net::io_context ioc(static_cast<int>(config.io_threads));
  EventHub events(ioc, db, std::chrono::milliseconds(2000));
  api::CrowdAssets crowd_assets(config.data_dir + "/models", &db, config.crowd_max_subdivision);
  ctx.crowd = &crowd_assets;
  ctx.crowd_limits.max_streams = config.max_crowd_streams;
  CrowdStreamer crowd(crowd_assets, ctx.crowd_limits);
  state.verify_api_key = [&db](std::string_view key) {
    auto conn = db.acquire();
    return store::verify_api_key(*conn, key).has_value();
  };
  register_routes(state, ctx, events, crowd);
  add_gauges(state);
  state.metrics.add_gauge("tourmap_crowd_streams", "Open crowd streams.",
                          [&crowd] { return static_cast<double>(crowd.streams()); });
  state.metrics.add_gauge("tourmap_crowd_frames_sent", "Crowd frames sent since the start (grows).",
                          [&crowd] { return static_cast<double>(crowd.frames_sent()); });

  tcp::acceptor acceptor(ioc);
  tcp::endpoint endpoint(net::ip::make_address(config.host), config.port);
  acceptor.open(endpoint.protocol());
  acceptor.set_option(net::socket_base::reuse_address(true));
  acceptor.bind(endpoint);
  acceptor.listen(net::socket_base::max_listen_connections);
  unsigned short port = acceptor.local_endpoint().port();
  std::printf("tourmap %s listening on http://%s:%u (db %s, web %s, %u io + %u compute threads)\n", TOURMAP_VERSION,
              config.host.c_str(), port, config.db_path.c_str(), config.web_root.c_str(), config.io_threads,
              state.pool.threads());
  std::fflush(stdout);
  if (on_listening) on_listening(port);

  accept_loop(acceptor, ioc, state);
  events.start();
  crowd.start();

  net::steady_timer drain(ioc);
  auto drain_deadline = std::chrono::steady_clock::now();
  std::function<void()> check_drained = [&] {
    bool idle = state.http_sessions.size() == 0 && state.ws_sessions.size() == 0 && state.in_flight == 0;
    if (idle) return;  // nothing left: run() returns once the last handlers finish
    if (std::chrono::steady_clock::now() >= drain_deadline) {
      std::fprintf(stderr, "shutdown: drain timeout with %ld request(s) in flight; stopping\n", state.in_flight.load());
      ioc.stop();
      return;
    }
    drain.expires_after(std::chrono::milliseconds(50));
    drain.async_wait([&](boost::system::error_code ec) {
      if (!ec) check_drained();
    });
  };

  net::signal_set signals(ioc, SIGINT, SIGTERM);
  signals.async_wait([&](boost::system::error_code ec, int sig) {
    if (ec) return;
    std::printf("shutdown: signal %d, draining (up to %.0f s)\n", sig, config.drain_timeout_s);
    std::fflush(stdout);
    state.stopping = true;
    boost::system::error_code ignored;
    acceptor.close(ignored);
    events.stop();
    crowd.request_stop();
    state.http_sessions.close_all();
    state.ws_sessions.close_all();
    drain_deadline = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(config.drain_timeout_s));
    check_drained();
  });

  std::vector<std::thread> threads;
  for (unsigned i = 1; i < config.io_threads; ++i) threads.emplace_back([&ioc] { ioc.run(); });
  ioc.run();
  for (auto& t : threads) t.join();

  crowd.stop();
  state.pool.shutdown();  // before the io_context goes: finished tasks post into it
  db.close_idle();
  std::printf("shutdown: done\n");
  std::fflush(stdout);
  return 0;
}

}  // namespace tourmap::server
