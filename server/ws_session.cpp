#include "ws_session.hpp"

#include "api/http.hpp"

#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>

#include <cstdio>

namespace tourmap::server {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace net = boost::asio;

WsSession::WsSession(net::ip::tcp::socket&& socket, ServerState& state, const WsEndpoint& endpoint, std::string path)
    : ws_(std::move(socket)), state_(state), endpoint_(endpoint), path_(std::move(path)) {}

WsSession::~WsSession() {
  if (registry_id_) state_.ws_sessions.remove(registry_id_);
}

void WsSession::accept(beast::http::request<beast::http::string_body>&& req) {
  if (state_.ws_sessions.size() >= state_.config.max_ws_connections) {
    // Refuse clearly: an HTTP 503 instead of the upgrade.
    auto res = std::make_shared<beast::http::response<beast::http::string_body>>(
        beast::http::status::service_unavailable, req.version());
    res->set(beast::http::field::content_type, "application/json");
    res->set(beast::http::field::retry_after, "5");
    res->body() = api::error_response(503, "too_many_connections",
                                      "the server holds " + std::to_string(state_.config.max_ws_connections) +
                                          " WebSocket connections, the most it may; retry later")
                      .body;
    res->prepare_payload();
    res->keep_alive(false);
    beast::http::async_write(ws_.next_layer(), *res, [self = shared_from_this(), res](beast::error_code, std::size_t) {
      beast::error_code ec;
      self->ws_.next_layer().socket().shutdown(net::ip::tcp::socket::shutdown_both, ec);
    });
    return;
  }
  std::weak_ptr<WsSession> weak = shared_from_this();
  auto executor = ws_.get_executor();
  registry_id_ = state_.ws_sessions.add([weak, executor] {
    net::post(executor, [weak] {
      if (auto self = weak.lock()) self->close(websocket::close_code::going_away, "server shutting down");
    });
  });
  // Ping a quiet client after 30 s; close it if nothing (not even a pong) arrives within 60 s.
  websocket::stream_base::timeout timeouts{};
  timeouts.handshake_timeout = std::chrono::seconds(30);
  timeouts.idle_timeout = std::chrono::seconds(60);
  timeouts.keep_alive_pings = true;
  ws_.set_option(timeouts);
  ws_.set_option(websocket::stream_base::decorator(
      [](websocket::response_type& res) { res.set(beast::http::field::server, "tourmap"); }));
  ws_.read_message_max(kMaxMessageBytes);
  auto shared_req = std::make_shared<beast::http::request<beast::http::string_body>>(std::move(req));
  ws_.async_accept(*shared_req, [self = shared_from_this(), shared_req](beast::error_code ec) {
    if (ec) return;
    self->open_ = true;
    try {
      if (self->endpoint_.on_open) self->endpoint_.on_open(self);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: WebSocket %s: %s\n", self->path_.c_str(), e.what());
      return self->close(websocket::close_code::internal_error, "internal error");
    }
    self->read();
    self->write_next();
  });
}

void WsSession::send_text(std::string message) { enqueue({std::move(message), false}); }
void WsSession::send_binary(std::string bytes) {
  ++binary_in_flight_;
  enqueue({std::move(bytes), true});
}

void WsSession::post_close(websocket::close_code code, std::string reason) {
  net::post(ws_.get_executor(), [self = shared_from_this(), code, reason = std::move(reason)]() mutable {
    self->close(code, std::move(reason));
  });
}

void WsSession::enqueue(Outgoing out) {
  net::dispatch(ws_.get_executor(), [self = shared_from_this(), out = std::move(out)]() mutable {
    if (self->closed_) {
      if (out.binary) --self->binary_in_flight_;
      return;
    }
    if (self->queue_.size() >= kMaxQueued) {
      // Drop the oldest message that is not being written (the front is, while writing_).
      auto victim = self->writing_ ? std::next(self->queue_.begin()) : self->queue_.begin();
      if (victim->binary) --self->binary_in_flight_;
      self->queue_.erase(victim);
      ++self->dropped_;
    }
    self->queue_.push_back(std::move(out));
    self->write_next();
  });
}

void WsSession::write_next() {
  if (!open_ || writing_ || queue_.empty() || closed_) return;
  writing_ = true;
  ws_.binary(queue_.front().binary);
  ws_.async_write(net::buffer(queue_.front().data), [self = shared_from_this()](beast::error_code ec, std::size_t) {
    self->writing_ = false;
    if (!self->queue_.empty()) {
      if (self->queue_.front().binary) --self->binary_in_flight_;
      self->queue_.pop_front();
    }
    if (ec) return self->finish();
    self->write_next();
  });
}

void WsSession::read() {
  ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, std::size_t bytes) {
    self->on_read(ec, bytes);
  });
}

void WsSession::on_read(beast::error_code ec, std::size_t) {
  if (ec == websocket::error::message_too_big) {
    close(websocket::close_code::too_big, "message exceeds " + std::to_string(kMaxMessageBytes) + " bytes");
    return;
  }
  if (ec) return finish();
  const auto now = std::chrono::steady_clock::now();
  if (now - window_start_ >= std::chrono::seconds(1)) {
    window_start_ = now;
    messages_in_window_ = 0;
  }
  if (++messages_in_window_ > kMaxMessagesPerSecond) {
    close(websocket::close_code::policy_error,
          "more than " + std::to_string(kMaxMessagesPerSecond) + " messages per second");
    return;
  }
  std::string text = beast::buffers_to_string(buffer_.data());
  buffer_.consume(buffer_.size());
  if (ws_.got_text() && endpoint_.on_text) {
    // Endpoints answer bad messages themselves; anything they throw is a fault of ours: the
    // client hears so and the connection closes (1011), the server goes on.
    try {
      endpoint_.on_text(shared_from_this(), text);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: WebSocket %s: %s\n", path_.c_str(), e.what());
      send_text(api::ws_error_message("internal", "internal error while handling the message"));
      close(websocket::close_code::internal_error, "internal error");
      return;
    }
  } else if (!ws_.got_text()) {
    send_text(api::ws_error_message("unsupported", "send JSON text messages, not binary ones", "type"));
  }
  read();
}

void WsSession::close(websocket::close_code code, std::string reason) {
  if (closed_) return;
  closed_ = true;
  closed_flag_ = true;
  // The message being written (if any) is accounted for when its write completes.
  for (auto it = writing_ && !queue_.empty() ? std::next(queue_.begin()) : queue_.begin(); it != queue_.end(); ++it)
    if (it->binary) --binary_in_flight_;
  if (writing_ && !queue_.empty()) queue_.erase(std::next(queue_.begin()), queue_.end());
  else queue_.clear();
  if (!open_) return finish();
  ws_.async_close(websocket::close_reason(code, reason), [self = shared_from_this()](beast::error_code) {
    self->finish();
  });
}

void WsSession::finish() {
  if (endpoint_.on_close && open_) endpoint_.on_close(shared_from_this());
  open_ = false;
  closed_ = true;
  closed_flag_ = true;
  if (registry_id_) {
    state_.ws_sessions.remove(registry_id_);
    registry_id_ = 0;
  }
}

}  // namespace tourmap::server
