#include "events.hpp"

#include "ws_session.hpp"

#include "api/http.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace tourmap::server {

EventHub::EventHub(boost::asio::io_context& ioc, store::DbPool& db, std::chrono::milliseconds interval)
    : timer_(ioc), db_(db), interval_(interval) {}

std::string EventHub::current_event(const char* type) {
  auto db = db_.acquire();
  auto st = db->prepare("SELECT id, kind, target_id FROM imports ORDER BY id DESC LIMIT 1");
  nlohmann::json ev = {{"type", type}, {"catalog_version", 0}};
  if (st.step()) {
    ev["catalog_version"] = st.int64(0);
    ev["last_import"] = {{"kind", st.text(1)}, {"target", st.text(2)}};
  }
  return ev.dump();
}

WsEndpoint EventHub::endpoint() {
  WsEndpoint ep;
  ep.on_open = [this](const std::shared_ptr<WsSession>& s) {
    {
      std::lock_guard lock(mutex_);
      subscribers_[s.get()] = s;
    }
    try {
      s->send_text(current_event("hello"));
    } catch (const std::exception& e) {
      s->send_text(api::ws_error_message("unavailable", std::string("cannot read the catalog: ") + e.what()));
    }
  };
  ep.on_text = [](const std::shared_ptr<WsSession>& s, const std::string& text) {
    auto msg = nlohmann::json::parse(text, nullptr, false);
    // Not value("type", ""): it throws for a non-string type, and nothing above on_text catches.
    if (msg.is_object() && msg.contains("type") && msg["type"] == "ping") {
      s->send_text(R"({"type":"pong"})");
      return;
    }
    s->send_text(api::ws_error_message("invalid_message", "type: expected {\"type\":\"ping\"}", "type"));
  };
  ep.on_close = [this](const std::shared_ptr<WsSession>& s) {
    std::lock_guard lock(mutex_);
    subscribers_.erase(s.get());
  };
  return ep;
}

void EventHub::start() {
  stopped_ = false;
  poll();
}

void EventHub::stop() {
  stopped_ = true;
  timer_.cancel();
}

void EventHub::poll() {
  if (stopped_) return;
  try {
    auto db = db_.acquire();
    // The newest import, and the number of cities and road networks (a delete changes those).
    auto st = db->prepare(
        "SELECT COALESCE(MAX(id), 0), (SELECT COUNT(*) FROM cities), (SELECT COUNT(*) FROM road_networks) "
        "FROM imports");
    st.step();
    const CatalogStamp latest{st.int64(0), st.int64(1), st.int64(2)};
    if (last_import_ >= 0 && latest != last_) broadcast(current_event("catalog"));
    last_ = latest;
    last_import_ = latest.last_import;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "events: cannot read the catalog version: %s\n", e.what());
  }
  timer_.expires_after(interval_);
  timer_.async_wait([this](boost::system::error_code ec) {
    if (!ec) poll();
  });
}

void EventHub::broadcast(const std::string& message) {
  std::lock_guard lock(mutex_);
  for (auto it = subscribers_.begin(); it != subscribers_.end();) {
    if (auto s = it->second.lock()) {
      s->send_text(message);
      ++it;
    } else {
      it = subscribers_.erase(it);
    }
  }
}

}  // namespace tourmap::server
