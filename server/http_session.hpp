#pragma once
// One HTTP/1.1 connection: reads requests (header within the idle timeout, then the body within
// the request timeout, with size limits), routes them, runs compute routes on the pool, writes
// responses, and hands WebSocket upgrades to WsSession.

#include "request_parser.hpp"
#include "respond.hpp"
#include "server_state.hpp"

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include <array>
#include <chrono>
#include <memory>
#include <optional>

namespace tourmap::server {

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(boost::asio::ip::tcp::socket&& socket, ServerState& state);
  ~HttpSession();
  void run();

 private:
  using Request = boost::beast::http::request<boost::beast::http::string_body>;
  using Response = boost::beast::http::response<boost::beast::http::string_body>;

  void read_header();
  void on_header(boost::beast::error_code ec);
  void read_body();
  void on_read(boost::beast::error_code ec);
  bool refuse_if_rate_limited(const Request& req);
  // Write routes need an API key; checked from the header alone, before the body is read.
  enum class WriteAccess { not_needed, granted, missing_key, bad_key, unavailable };
  WriteAccess check_write_access(const Request& header) const;
  void refuse_write(const RequestFacts& facts);
  std::size_t body_limit() const;  // for the request being read
  void handle(Request&& req);
  void answer_preflight(const RequestFacts& facts);
  void add_cors_headers(Response& res) const;
  // Runs a light or heavy route on its pool; the answer comes back to this connection's strand.
  void run_on_pool(const api::Route& route, api::Request&& areq, const RequestFacts& facts);
  void refuse_admission(ComputePool::Admission admission, bool heavy, const RequestFacts& facts);
  // While a heavy request computes, the socket is watched: a client that closes it (FIN or
  // RST) sets `cancelled`, and the computation stops at its next check (util::check_stop).
  void watch_client(std::shared_ptr<std::atomic<bool>> cancelled);
  void stop_watching_client();
  // The client left before its answer: nothing is written; counted as 499 (client closed).
  void finish_abandoned();
  void send(Response&& res, const std::string& route_label);
  void on_write(bool close, boost::beast::error_code ec, std::size_t bytes);
  void fail_read(int status, const std::string& code, const std::string& message);
  void shutdown_requested();
  void close();
  // Closes after a refusal whose request was not read to its end (a body or trailer still on
  // its way): stops sending, then reads and discards for a while before closing. Closing at
  // once would reset the connection, and the client could lose the answer (nginx's
  // "lingering close"). At most kLingerBytes or kLingerSeconds.
  void linger_close();
  void linger_more();
  static constexpr std::size_t kLingerBytes = 1u << 20;
  static constexpr int kLingerSeconds = 2;

  boost::beast::tcp_stream stream_;
  boost::beast::flat_buffer buffer_;  // bounded: a header or a chunked trailer must fit in it
  std::optional<RequestParser> parser_;
  ServerState& state_;
  std::uint64_t registry_id_ = 0;
  std::string remote_;  // the peer's address
  std::string client_;  // the request's client: remote_, or from X-Forwarded-For via a trusted proxy
  WriteAccess write_access_ = WriteAccess::not_needed;

  // The request being answered (for the access log, metrics and response finishing).
  bool busy_ = false;
  bool watching_client_ = false;  // an async_wait for the client's FIN is pending
  bool unread_input_ = false;     // refused before the request was read to its end
  std::size_t lingered_ = 0;      // bytes discarded by linger_close
  std::array<char, 8192> discard_{};
  bool counted_ = false;  // counted in state_.in_flight
  std::chrono::steady_clock::time_point started_;
  std::string method_, target_, route_label_;
  std::string origin_;  // the request's Origin header (CORS)
  std::shared_ptr<Response> response_;
};

}  // namespace tourmap::server
