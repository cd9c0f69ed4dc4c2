#pragma once
// One WebSocket connection. Text and binary messages can be sent from any thread; they are
// queued on the session's strand and written one at a time. The queue is bounded: when a
// client reads too slowly the oldest queued messages are dropped (counted), never an unbounded
// backlog.

#include "server_state.hpp"

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <atomic>
#include <chrono>
#include <deque>
#include <memory>
#include <string>

namespace tourmap::server {

class WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  static constexpr std::size_t kMaxQueued = 16;
  static constexpr std::size_t kMaxMessageBytes = 64 * 1024;
  // Any endpoint: more messages than this in one second close the connection (1008). Endpoints
  // may be stricter (the crowd stream allows 60 views and 60 acks per second).
  static constexpr unsigned kMaxMessagesPerSecond = 200;

  WsSession(boost::asio::ip::tcp::socket&& socket, ServerState& state, const WsEndpoint& endpoint,
            std::string path);
  ~WsSession();

  void accept(boost::beast::http::request<boost::beast::http::string_body>&& req);
  void send_text(std::string message);
  void send_binary(std::string bytes);
  // Closes with a reason (a WebSocket close frame), e.g. on shutdown.
  void close(boost::beast::websocket::close_code code, std::string reason);

  std::size_t dropped() const { return dropped_; }
  // Binary messages queued or being written (any thread): a frame producer renders the next
  // frame only when this is 0, so a slow client gets the newest frame, never a backlog.
  std::size_t binary_in_flight() const { return binary_in_flight_.load(); }
  bool is_closed() const { return closed_flag_.load(); }
  // close() from any thread.
  void post_close(boost::beast::websocket::close_code code, std::string reason);
  const std::string& path() const { return path_; }

 private:
  struct Outgoing {
    std::string data;
    bool binary;
  };
  void enqueue(Outgoing out);
  void write_next();
  void read();
  void on_read(boost::beast::error_code ec, std::size_t bytes);
  void finish();

  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
  ServerState& state_;
  const WsEndpoint& endpoint_;
  std::string path_;
  boost::beast::flat_buffer buffer_;
  std::deque<Outgoing> queue_;
  bool writing_ = false;
  bool open_ = false;
  bool closed_ = false;
  std::size_t dropped_ = 0;
  std::chrono::steady_clock::time_point window_start_{};  // the current one-second window
  unsigned messages_in_window_ = 0;
  std::atomic<std::size_t> binary_in_flight_{0};
  std::atomic<bool> closed_flag_{false};
  std::uint64_t registry_id_ = 0;
};

}  // namespace tourmap::server
