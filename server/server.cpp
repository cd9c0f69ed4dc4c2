#include "server.hpp"

#include "events.hpp"
#include "http_session.hpp"
#include "routes_table.hpp"
#include "server_state.hpp"
#include "ws_session.hpp"

#include "api/upload.hpp"
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
                          [&state] { return static_cast<double>(state.compute_pool.queued()); });
  state.metrics.add_gauge("tourmap_compute_busy", "Compute threads running a request.",
                          [&state] { return static_cast<double>(state.compute_pool.busy()); });
  state.metrics.add_gauge("tourmap_compute_clients", "Client addresses with compute requests queued or running.",
                          [&state] { return static_cast<double>(state.compute_pool.clients()); });
  state.metrics.add_gauge("tourmap_compute_expired_in_queue",
                          "Compute requests answered 503 because they waited past the deadline (grows).",
                          [&state] { return static_cast<double>(state.compute_pool.expired_in_queue()); });
  state.metrics.add_gauge("tourmap_read_queued", "Reads waiting for a read thread.",
                          [&state] { return static_cast<double>(state.read_pool.queued()); });
  state.metrics.add_gauge("tourmap_read_busy", "Read threads running a request.",
                          [&state] { return static_cast<double>(state.read_pool.busy()); });
  state.metrics.add_gauge("tourmap_io_handler_exceptions",
                          "Exceptions that escaped a connection's handlers and were caught by an IO thread (grows).",
                          [&state] { return static_cast<double>(state.handler_exceptions.load()); });
  state.metrics.add_gauge("tourmap_rate_limit_clients",
                          "Client addresses the rate limiter tracks (requests refused: status 429, route rate_limited).",
                          [&state] {
                            state.rate_limiter.evict_idle(std::chrono::steady_clock::now());
                            return static_cast<double>(state.rate_limiter.tracked());
                          });
}

// The background improvement of default layouts (api/metro_service.hpp, MetroLimits).
void add_improvement_gauges(ServerState& state, api::MetroService& metro) {
  using Stats = api::MetroService::ImprovementStats;
  const struct {
    const char* name;
    const char* help;
    double (*read)(const Stats&);
  } gauges[] = {
      {"tourmap_layout_improvements_queued", "Default layouts waiting for their background MIP improvement.",
       [](const Stats& s) { return static_cast<double>(s.queue.queued); }},
      {"tourmap_layout_improvements_running", "Background MIP improvements running (at most 1).",
       [](const Stats& s) { return static_cast<double>(s.queue.running); }},
      {"tourmap_layout_improvements_scheduled", "Background MIP improvements scheduled (grows).",
       [](const Stats& s) { return static_cast<double>(s.scheduled); }},
      {"tourmap_layout_improvements_applied", "Background MIP results that replaced a cached layout (grows).",
       [](const Stats& s) { return static_cast<double>(s.improved); }},
      {"tourmap_layout_improvements_not_better", "Background MIP results not accepted: the fast layout stays (grows).",
       [](const Stats& s) { return static_cast<double>(s.not_improved); }},
      {"tourmap_layout_improvements_dropped", "Waiting improvements dropped because the queue was full (grows).",
       [](const Stats& s) { return static_cast<double>(s.queue.dropped); }},
      {"tourmap_layout_improvements_stale", "Improvements dropped because the city was imported again (grows).",
       [](const Stats& s) { return static_cast<double>(s.stale); }},
      {"tourmap_layout_improvements_failed", "Improvements that failed with an error (grows).",
       [](const Stats& s) { return static_cast<double>(s.queue.failed); }},
  };
  for (const auto& g : gauges)
    state.metrics.add_gauge(g.name, g.help, [&metro, read = g.read] { return read(metro.improvement_stats()); });
}

// How POI cluster trees were made (api/cluster_tree_reuse.hpp).
void add_cluster_tree_gauges(ServerState& state, api::MetroService& metro) {
  state.metrics.add_gauge("tourmap_cluster_trees_built", "POI cluster trees built from scratch (grows).",
                          [&metro] { return static_cast<double>(metro.cluster_trees_built()); });
  state.metrics.add_gauge("tourmap_cluster_trees_updated",
                          "POI cluster trees updated from the one served for the previous city version (grows).",
                          [&metro] { return static_cast<double>(metro.cluster_trees_updated()); });
}

// Accepts connections. When accepting fails (the process is out of file descriptors: EMFILE,
// or the system: ENFILE, ENOBUFS, ENOMEM), the pending connection stays in the listen queue
// and the next accept would fail at once: without a pause the loop spins a core at 100 %.
// It waits 100 ms instead (and says so once per episode); connections are accepted again as
// soon as descriptors are free.
struct AcceptLoop {
  tcp::acceptor& acceptor;
  net::io_context& ioc;
  ServerState& state;
  net::steady_timer pause{ioc};
  bool failing = false;

  void next() {
    acceptor.async_accept(net::make_strand(ioc), [this](boost::system::error_code ec, tcp::socket socket) {
      if (ec == net::error::operation_aborted || !acceptor.is_open()) return;
      if (!ec) {
        if (failing) std::fprintf(stderr, "accept: accepting connections again\n");
        failing = false;
        // Without TCP_NODELAY the last part of a large answer (a deformed network's positions)
        // waits for the client's delayed ACK: ~40 ms on every answer, measured in the drag bench.
        boost::system::error_code option_ec;
        socket.set_option(tcp::no_delay(true), option_ec);  // a refusal only costs latency
        std::make_shared<HttpSession>(std::move(socket), state)->run();
        return next();
      }
      if (!failing) std::fprintf(stderr, "accept: %s; pausing 100 ms between attempts\n", ec.message().c_str());
      failing = true;
      pause.expires_after(std::chrono::milliseconds(100));
      pause.async_wait([this](boost::system::error_code wait_ec) {
        if (!wait_ec) next();
      });
    });
  }
};

// Runs the io_context until it stops. An exception out of a handler (none is expected: the
// connections catch what their handlers throw) is logged and counted; its connection is
// dropped by the unwinding and the thread goes on serving the others instead of ending the
// process.
void run_io(net::io_context& ioc, ServerState& state) {
  for (;;) {
    try {
      ioc.run();
      return;
    } catch (const std::exception& e) {
      ++state.handler_exceptions;
      std::fprintf(stderr, "error: a connection handler threw (connection dropped): %s\n", e.what());
    } catch (...) {
      ++state.handler_exceptions;
      std::fprintf(stderr, "error: a connection handler threw a non-standard exception (connection dropped)\n");
    }
  }
}

}  // namespace

int serve(const Config& config, const std::function<void(unsigned short)>& on_listening) {
  store::DbPool db(config.db_path);
  {
    auto conn = db.acquire();
    for (const auto& name : store::migrate(*conn)) std::printf("migrated: %s\n", name.c_str());
  }
  if (auto stale = api::remove_stale_uploads())
    std::printf("removed %zu upload director%s left by stopped servers\n", stale, stale == 1 ? "y" : "ies");
  api::Catalog catalog(db);
  ServerState state(config);  // declared before the io_context: sessions refer to it until the end
  api::DeformService deform(catalog);
  api::MetroLimits metro_limits;
  metro_limits.improve_mip_s = config.improve_mip_s;
  api::MetroService metro(catalog, api::child_process_mip_solver("/proc/self/exe"), metro_limits,
                          api::child_process_mip_solver("/proc/self/exe", metro_limits.improve_mip_grace_s,
                                                                       api::ChildClock::cpu));
  api::AppContext ctx{db, catalog, deform, metro, TOURMAP_VERSION};
  net::io_context ioc(static_cast<int>(config.io_threads));
  EventHub events(ioc, db, std::chrono::milliseconds(2000));
  // Default layouts are improved in the background and announced on /api/v1/events. The
  // improver's thread publishes into `events`: it is stopped before `events` goes (also when
  // serve() leaves by an exception), by this guard declared after it.
  metro.on_layout_improved([&events](const std::string& event) { events.publish(event); });
  struct StopImprovements {
    api::MetroService& metro;
    ~StopImprovements() { metro.stop_improvements(); }
  } stop_improvements{metro};
  // Handlers publish import progress into `events` until it goes (a compute thread may outlive it).
  ctx.events->attach([&events](const std::string& event) { events.publish(event); });
  struct DetachEvents {
    api::EventSink& sink;
    ~DetachEvents() { sink.detach(); }
  } detach_events{*ctx.events};
  api::CrowdAssets crowd_assets(config.data_dir + "/models", &db, config.crowd_max_subdivision);
  ctx.crowd = &crowd_assets;
  ctx.crowd_limits.max_streams = config.max_crowd_streams;
  ctx.import_limits = import_limits_of(config);
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
  state.metrics.add_gauge("tourmap_crowd_frames_unchanged",
                          "Crowd frames rendered but not sent: the same picture as the stream's last (grows).",
                          [&crowd] { return static_cast<double>(crowd.frames_unchanged()); });
  state.metrics.add_gauge("tourmap_deform_cache_bytes",
                          "Bytes the deformation caches hold (networks, prepared systems, answers), as charged.",
                          [&deform] {
                            const auto s = deform.cache_stats();
                            return static_cast<double>(s.network_bytes + s.prepared_bytes + s.result_bytes);
                          });
  add_improvement_gauges(state, metro);
  add_cluster_tree_gauges(state, metro);
  state.metrics.add_gauge("tourmap_crowd_variants_evicted",
                          "Prepared crowd scene variants (scene, count) evicted to make room (grows).",
                          [&crowd] { return static_cast<double>(crowd.variants_evicted()); });

  tcp::acceptor acceptor(ioc);
  tcp::endpoint endpoint(net::ip::make_address(config.host), config.port);
  acceptor.open(endpoint.protocol());
  acceptor.set_option(net::socket_base::reuse_address(true));
  acceptor.bind(endpoint);
  acceptor.listen(net::socket_base::max_listen_connections);
  unsigned short port = acceptor.local_endpoint().port();
  std::printf("tourmap %s listening on http://%s:%u (db %s, web %s, %u io + %u read + %u compute threads)\n",
              TOURMAP_VERSION, config.host.c_str(), port, config.db_path.c_str(), config.web_root.c_str(),
              config.io_threads, state.read_pool.threads(), state.compute_pool.threads());
  std::fflush(stdout);
  if (on_listening) on_listening(port);

  AcceptLoop accept_loop{acceptor, ioc, state};
  accept_loop.next();
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
    metro.request_stop_improvements();
    crowd.request_stop();
    state.http_sessions.close_all();
    state.ws_sessions.close_all();
    drain_deadline = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(config.drain_timeout_s));
    check_drained();
  });

  std::vector<std::thread> threads;
  for (unsigned i = 1; i < config.io_threads; ++i) threads.emplace_back([&ioc, &state] { run_io(ioc, state); });
  run_io(ioc, state);
  for (auto& t : threads) t.join();

  crowd.stop();
  metro.stop_improvements();
  state.compute_pool.shutdown();  // before the io_context goes: finished tasks post into it
  state.read_pool.shutdown();
  db.close_idle();
  std::printf("shutdown: done\n");
  std::fflush(stdout);
  return 0;
}

}  // namespace tourmap::server
