#pragma once
// WS /api/v1/events: tells connected clients when the catalog changes (a city or road network
// was imported or deleted, by this process or another one writing the same database), so a client can
// refresh without polling. The store is polled every `interval` for the newest import.
// Other parts of the server publish their own events through publish() (the metro service's
// `layout_improved`, when a background MIP replaced a cached default layout).

#include "server_state.hpp"

#include "store/db_pool.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include <chrono>
#include <map>
#include <memory>
#include <mutex>

namespace tourmap::server {

class EventHub {
 public:
  EventHub(boost::asio::io_context& ioc, store::DbPool& db, std::chrono::milliseconds interval);
  WsEndpoint endpoint();
  void start();
  void stop();
  // Sends `message` (a JSON object with a "type") to every connected client; any thread.
  void publish(const std::string& message) { broadcast(message); }

 private:
  void poll();
  void broadcast(const std::string& message);
  std::string current_event(const char* type);

  boost::asio::steady_timer timer_;
  store::DbPool& db_;
  std::chrono::milliseconds interval_;
  std::mutex mutex_;
  std::map<const WsSession*, std::weak_ptr<WsSession>> subscribers_;
  struct CatalogStamp {
    std::int64_t last_import = 0, cities = 0, road_networks = 0;
    bool operator==(const CatalogStamp&) const = default;
  };
  std::int64_t last_import_ = -1;  // -1: not polled yet
  CatalogStamp last_;
  bool stopped_ = false;
};

}  // namespace tourmap::server
