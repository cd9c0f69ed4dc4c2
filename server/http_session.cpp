#include "http_session.hpp"

#include "respond.hpp"
#include "url.hpp"
#include "ws_session.hpp"

#include "util/stop.hpp"

#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/websocket.hpp>

#include <sys/socket.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <limits>

namespace tourmap::server {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using Clock = std::chrono::steady_clock;

namespace {

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

RequestFacts facts_of(const http::request<http::string_body>& req) {
  RequestFacts f;
  f.method = req.method();
  f.version = req.version();
  f.keep_alive = req.keep_alive();
  f.accept_encoding = std::string(req[http::field::accept_encoding]);
  f.if_none_match = std::string(req[http::field::if_none_match]);
  return f;
}

// nginx's status for "the client closed the connection before the answer": metrics and the
// access log only, never sent.
constexpr int kClientClosedRequest = 499;

// Runs a handler, turning exceptions into error responses: ApiError keeps its status; a
// computation stopped at its deadline is a 503, one whose client left a 499; anything else is
// a server fault (500), logged, never a crash.
api::Response run_handler(const api::Route& route, api::Request& req, double timeout_s) {
  try {
    return route.handler(req);
  } catch (const api::ApiError& e) {
    return api::error_response(e);
  } catch (const util::Stopped& e) {
    if (e.reason == util::Stopped::Reason::client_gone) {
      api::Response gone;
      gone.status = kClientClosedRequest;
      return gone;
    }
    char text[160];
    std::snprintf(text, sizeof text,
                  "the computation was stopped at its limit of %g s; retry later or ask for less (a coarser grid, "
                  "a smaller window, a shorter time limit)",
                  timeout_s);
    auto r = api::error_response(503, "timeout", text);
    r.headers.emplace_back("Retry-After", "5");
    return r;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s %s: %s\n", req.method.c_str(), req.path.c_str(), e.what());
    return api::error_response(500, "internal", "internal error while handling the request");
  }
}

// Compute routes whose body is at most this big are finished (ETag, gzip) on the connection's IO
// thread, bigger ones (road networks, deformations) on the pool. Bounded: deflating 32 KiB takes
// well under a millisecond. Under the cluster load (7 KB answers, 2 cores) it cut the server's
// context switches per request from ~2.8 to ~1 and its CPU per request by ~20 %: the pool
// threads hand each result over after the handler instead of after the handler and the deflate,
// so neither the pool nor the IO threads idle (and sleep, and get woken) as often.
constexpr std::size_t kFinishOnIoMaxBytes = 32u << 10;

// finish_response, with a failure in it (gzip) turned into a 500.
http::response<http::string_body> finish_or_fail(api::Response r, const RequestFacts& facts, const Config& config) {
  try {
    return finish_response(std::move(r), facts, config);
  } catch (const std::exception& e) {
    return finish_response(api::error_response(500, "internal", e.what()), facts, config);
  }
}

}  // namespace

HttpSession::HttpSession(net::ip::tcp::socket&& socket, ServerState& state)
    : stream_(std::move(socket)), buffer_(state.config.max_header_bytes + (8u << 10)), state_(state) {
  beast::error_code ec;
  auto ep = stream_.socket().remote_endpoint(ec);
  remote_ = ec ? "-" : ep.address().to_string();
  client_ = remote_;
}

HttpSession::~HttpSession() {
  if (registry_id_) state_.http_sessions.remove(registry_id_);
}

void HttpSession::run() {
  std::weak_ptr<HttpSession> weak = shared_from_this();
  auto executor = stream_.get_executor();
  registry_id_ = state_.http_sessions.add([weak, executor] {
    net::post(executor, [weak] {
      if (auto self = weak.lock()) self->shutdown_requested();
    });
  });
  net::dispatch(stream_.get_executor(), beast::bind_front_handler(&HttpSession::read_header, shared_from_this()));
}

void HttpSession::read_header() {
  if (state_.stopping) return close();
  origin_.clear();
  client_ = remote_;
  write_access_ = WriteAccess::not_needed;
  parser_.emplace(state_.config.max_header_fields, state_.config.max_header_bytes);
  // Beast checks a Content-Length against the limit while parsing the header, before we know
  // whether the request is an authorised upload: the limit is applied in on_header. (Not
  // boost::none: Beast 1.74 compares the length against the optional, and none is the smallest.)
  parser_->body_limit(std::numeric_limits<std::uint64_t>::max());
  parser_->header_limit(static_cast<std::uint32_t>(state_.config.max_header_bytes));
  stream_.expires_after(seconds(state_.config.idle_timeout_s));
  http::async_read_header(stream_, buffer_, *parser_,
                          [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_header(ec); });
}

void HttpSession::on_header(beast::error_code ec) {
  if (ec) return on_read(ec);
  busy_ = true;
  started_ = Clock::now();
  const auto& header = parser_->get();
  if (state_.trusted_proxies.enabled())
    client_ = state_.trusted_proxies.client_of(remote_, header["X-Forwarded-For"]);
  write_access_ = check_write_access(header);
  // An authorised write may carry an upload (an OSM extract) bigger than the body limit.
  const std::size_t limit = body_limit();
  parser_->body_limit(limit);  // counts down chunked bodies
  if (auto length = parser_->content_length(); length && *length > limit) return on_read(http::error::body_limit);
  stream_.expires_after(seconds(state_.config.request_timeout_s));
  // A client that waits for "100 Continue" before sending a body (curl does above 1 MiB) gets it
  // when the body is welcome, and a refused write its 401 at once, without the upload.
  if (beast::iequals(header[http::field::expect], "100-continue")) {
    if (write_access_ != WriteAccess::not_needed && write_access_ != WriteAccess::granted)
      return on_read(http::error::body_limit);  // answered by refuse_write, connection closed
    auto go_on = std::make_shared<http::response<http::empty_body>>(http::status::continue_, header.version());
    return http::async_write(stream_, *go_on, [self = shared_from_this(), go_on](beast::error_code ec2, std::size_t) {
      if (ec2) return self->close();
      self->read_body();
    });
  }
  read_body();
}

void HttpSession::read_body() {
  http::async_read(stream_, buffer_, *parser_,
                   [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
}

void HttpSession::fail_read(int status, const std::string& code, const std::string& message) {
  busy_ = true;
  started_ = Clock::now();
  method_ = "-";
  target_ = "-";
  RequestFacts facts;
  facts.keep_alive = false;  // the stream is not in a known state: answer and close
  unread_input_ = true;
  send(finish_response(api::error_response(status, code, message), facts, state_.config), "invalid");
}

void HttpSession::on_read(beast::error_code ec) {
  if (ec == http::error::end_of_stream || ec == net::error::operation_aborted || ec == beast::error::timeout ||
      ec == net::error::connection_reset || ec == net::error::eof)
    return close();
  // A refused write whose body is too big to read, or whose client waits for 100 Continue.
  if (ec == http::error::body_limit && write_access_ != WriteAccess::not_needed &&
      write_access_ != WriteAccess::granted) {
    busy_ = true;
    method_ = std::string(parser_->get().method_string());
    target_ = std::string(parser_->get().target());
    RequestFacts facts;
    facts.keep_alive = false;  // the body was not read
    unread_input_ = true;
    route_label_ = "unauthorized";
    return refuse_write(facts);
  }
  if (ec == http::error::body_limit)
    return fail_read(413, "payload_too_large", "request body exceeds " + std::to_string(body_limit()) + " bytes");
  // header_limit: the header's bytes, or the header and trailer fields' count, or the trailer's
  // bytes; buffer_overflow: a header or trailer that outgrew the connection's buffer.
  if (ec == http::error::header_limit || ec == http::error::buffer_overflow)
    return fail_read(431, "header_too_large",
                     "request header or chunked trailer exceeds " + std::to_string(state_.config.max_header_bytes) +
                         " bytes or " + std::to_string(state_.config.max_header_fields) + " fields");
  if (ec) return fail_read(400, "bad_request", "malformed HTTP request: " + ec.message());

  Request req = parser_->release();
  origin_ = std::string(req[http::field::origin]);
  if (refuse_if_rate_limited(req)) return;
  if (beast::websocket::is_upgrade(req)) {
    auto target = parse_target(req.target());
    auto it = target ? state_.ws_endpoints.find(target->path) : state_.ws_endpoints.end();
    if (it == state_.ws_endpoints.end()) {
      busy_ = true;
      method_ = "GET";
      target_ = std::string(req.target());
      send(finish_response(api::error_response(404, "not_found", "no WebSocket endpoint at this path"),
                           facts_of(req), state_.config),
           "ws_unmatched");
      return;
    }
    stream_.expires_never();
    auto ws = std::make_shared<WsSession>(stream_.release_socket(), state_, it->second, it->first);
    ws->accept(std::move(req));
    return;
  }
  handle(std::move(req));
}

// Every request but the health and metrics reads takes a token from its client address's
// bucket first; without one it gets 429 with Retry-After, before any routing or upgrade.
bool HttpSession::refuse_if_rate_limited(const Request& req) {
  if (!state_.rate_limiter.enabled()) return false;
  const std::string_view target = req.target();
  const std::string_view path = target.substr(0, target.find('?'));
  if ((req.method() == http::verb::get || req.method() == http::verb::head) && (path == "/healthz" || path == "/metrics"))
    return false;
  auto decision = state_.rate_limiter.acquire(client_, Clock::now());
  if (decision.allowed) return false;
  const long retry_s = RateLimiter::retry_after_header(decision.retry_after_s);
  busy_ = true;
  method_ = std::string(req.method_string());
  target_ = std::string(target);
  char limits[96];
  std::snprintf(limits, sizeof limits, "%g requests per second, bursts of %g", state_.rate_limiter.options().rate,
                state_.rate_limiter.options().burst);
  auto r = api::error_response(429, "rate_limited",
                               "too many requests from this address (" + std::string(limits) + "); retry in " +
                                   std::to_string(retry_s) + " s");
  r.headers.emplace_back("Retry-After", std::to_string(retry_s));
  auto facts = facts_of(req);
  if (beast::websocket::is_upgrade(req)) facts.keep_alive = false;  // a refused upgrade ends the connection
  send(finish_response(std::move(r), facts, state_.config), "rate_limited");
  return true;
}

void HttpSession::handle(Request&& req) {
  ++state_.in_flight;
  counted_ = true;
  method_ = std::string(req.method_string());
  target_ = std::string(req.target());
  auto facts = facts_of(req);
  // A CORS preflight is answered here for any path (the request it announces is routed when
  // it comes). With CORS off, OPTIONS goes to the router like any other method.
  if (state_.cors.enabled() && req.method() == http::verb::options && !origin_.empty() &&
      req.count(http::field::access_control_request_method))
    return answer_preflight(facts);
  auto target = parse_target(req.target());
  if (!target) {
    route_label_ = "invalid";
    return send(finish_response(api::error_response(400, "invalid_target", "malformed request target", "path"), facts,
                                state_.config),
                route_label_);
  }

  api::Request areq;
  areq.method = method_;
  areq.path = std::move(target->path);
  areq.query = std::move(target->query);
  areq.body = std::move(req.body());
  areq.content_type = std::string(req[http::field::content_type]);
  areq.accept = std::string(req[http::field::accept]);

  auto match = state_.router.match(areq);
  if (!match.route) {
    bool api_path = areq.path.rfind("/api/", 0) == 0 || areq.path == "/healthz" || areq.path == "/metrics";
    if (!match.allowed.empty()) {
      route_label_ = "method_not_allowed";
      std::string allow;
      for (const auto& m : match.allowed) allow += (allow.empty() ? "" : ", ") + m;
      auto r = api::error_response(405, "method_not_allowed", areq.method + " is not allowed here", "method");
      r.headers.emplace_back("Allow", allow);
      return send(finish_response(std::move(r), facts, state_.config), route_label_);
    }
    route_label_ = api_path ? "unmatched" : "static";
    std::optional<api::Response> file;
    if (!api_path && (req.method() == http::verb::get || req.method() == http::verb::head))
      file = state_.static_files.serve(areq.path);
    auto r = file ? std::move(*file) : api::error_response(404, "not_found", "nothing at " + areq.path, "path");
    return send(finish_response(std::move(r), facts, state_.config), route_label_);
  }

  const api::Route& route = *match.route;
  route_label_ = route.pattern;
  if (route.access == api::Access::api_key && write_access_ != WriteAccess::granted) return refuse_write(facts);
  if (route.exec == api::Exec::io) {
    auto r = run_handler(route, areq, 0.0);
    return send(finish_response(std::move(r), facts, state_.config), route_label_);
  }

  run_on_pool(route, std::move(areq), facts);
}

void HttpSession::run_on_pool(const api::Route& route, api::Request&& areq, const RequestFacts& facts) {
  const bool heavy = route.exec == api::Exec::heavy;
  const Config& config = state_.config;
  ComputePool& pool = heavy ? state_.compute_pool : state_.read_pool;
  const double wait_s = heavy ? config.compute_deadline_s : config.read_deadline_s;
  const double timeout_s = heavy ? config.compute_timeout_s : 0.0;
  auto cancelled = std::make_shared<std::atomic<bool>>(false);
  auto self = shared_from_this();
  // The task computes on the pool and hands back what posts the answer to this connection's
  // strand: the pool runs that once the client's slot is free (compute_pool.hpp).
  auto task = [self, &route, areq = std::move(areq), facts, cancelled, wait_s, timeout_s](
                  bool expired) mutable -> ComputePool::Then {
    api::Response r;
    if (expired) {
      char text[96];
      std::snprintf(text, sizeof text, "the server is busy: the request waited %g s for a worker; retry shortly", wait_s);
      r = api::error_response(503, "overloaded", text);
      r.headers.emplace_back("Retry-After", "2");
    } else if (cancelled->load()) {
      r.status = kClientClosedRequest;  // left while queued: not computed at all
    } else {
      util::StopToken token;
      token.cancelled = cancelled.get();
      if (timeout_s > 0) token.deadline = util::StopToken::Clock::now() + seconds(timeout_s);
      util::StopScope scope(token);
      r = run_handler(route, areq, timeout_s);
    }
    if (r.status == kClientClosedRequest)
      return [self] { net::post(self->stream_.get_executor(), [self] { self->finish_abandoned(); }); };
    if (r.body.size() <= kFinishOnIoMaxBytes) {
      return [self, r = std::make_shared<api::Response>(std::move(r)), facts] {
        net::post(self->stream_.get_executor(), [self, r, facts] {
          self->stop_watching_client();
          self->send(finish_or_fail(std::move(*r), facts, self->state_.config), self->route_label_);
        });
      };
    }
    auto res = std::make_shared<Response>(finish_or_fail(std::move(r), facts, self->state_.config));
    return [self, res] {
      net::post(self->stream_.get_executor(), [self, res] {
        self->stop_watching_client();
        self->send(std::move(*res), self->route_label_);
      });
    };
  };
  const auto admission = pool.admit(std::move(task), Clock::now() + seconds(wait_s), client_);
  if (admission != ComputePool::Admission::accepted) return refuse_admission(admission, heavy, facts);
  if (heavy) watch_client(std::move(cancelled));
}

void HttpSession::refuse_admission(ComputePool::Admission admission, bool heavy, const RequestFacts& facts) {
  api::Response r;
  if (admission == ComputePool::Admission::client_busy && heavy) {
    const auto cap = state_.config.max_compute_per_client;
    r = api::error_response(429, "too_many_computations",
                            "this address already has " + std::to_string(cap) + " expensive request" +
                                (cap == 1 ? "" : "s") +
                                " (layouts, deformations, rasters, clusters, imports) queued or running, the most "
                                "it may have; send the next when one is answered");
    r.headers.emplace_back("Retry-After", "1");
  } else if (admission == ComputePool::Admission::client_busy) {
    r = api::error_response(429, "too_many_reads",
                            "this address already has " + std::to_string(state_.config.max_reads_per_client) +
                                " reads queued or running, the most it may have; retry shortly");
    r.headers.emplace_back("Retry-After", "1");
  } else if (admission == ComputePool::Admission::stopping) {
    r = api::error_response(503, "unavailable", "the server is shutting down; retry shortly");
    r.headers.emplace_back("Retry-After", "1");
  } else {
    r = api::error_response(503, "overloaded",
                            std::string("the server is busy: its ") + (heavy ? "compute" : "read") +
                                " queue is full; retry shortly");
    r.headers.emplace_back("Retry-After", "1");
  }
  send(finish_response(std::move(r), facts, state_.config), route_label_);
}

// Watches the connection while its request computes, to stop the computation when the client
// leaves. The peek must not block: a wait can complete without anything to read (a readiness
// event left over from the request's own bytes, which were read already), and a blocking peek
// then waits for the client's next bytes while holding this connection's strand, so the
// answer could never be sent (seen as a test request unanswered for 60 s).
void HttpSession::watch_client(std::shared_ptr<std::atomic<bool>> cancelled) {
  watching_client_ = true;
  stream_.socket().async_wait(net::socket_base::wait_read, [self = shared_from_this(), cancelled](beast::error_code ec) {
    // Stopped (the answer is ready; also when this completion was queued before the cancel) or
    // a socket error.
    if (ec || !self->watching_client_) return;
    self->watching_client_ = false;
    char byte = 0;
    const auto n = ::recv(self->stream_.socket().native_handle(), &byte, 1, MSG_PEEK | MSG_DONTWAIT);
    if (n > 0) return;  // the client pipelined its next request: kept for later (a peek does not consume it)
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))
      return self->watch_client(cancelled);  // nothing to read after all: watch on
    cancelled->store(true);                  // end of stream or a socket error: the client left
  });
}

void HttpSession::stop_watching_client() {
  if (!watching_client_) return;
  watching_client_ = false;
  beast::error_code ec;
  stream_.socket().cancel(ec);  // only the wait is pending while a request computes
}

void HttpSession::finish_abandoned() {
  stop_watching_client();
  route_label_ = route_label_.empty() ? "unmatched" : route_label_;
  const double ready_s = std::chrono::duration<double>(Clock::now() - started_).count();
  state_.metrics.observe(route_label_, method_, kClientClosedRequest, ready_s);
  const double ms = ready_s * 1000.0;
  state_.access_log.write(client_, method_, target_, kClientClosedRequest, 0, ms);
  if (counted_) --state_.in_flight;
  counted_ = false;
  busy_ = false;
  close();
}

std::size_t HttpSession::body_limit() const {
  return write_access_ == WriteAccess::granted ? state_.config.max_upload_bytes : state_.config.max_body_bytes;
}

HttpSession::WriteAccess HttpSession::check_write_access(const Request& header) const {
  // Reads are never write routes: skip the route match (hot path).
  if (header.method() == http::verb::get || header.method() == http::verb::head) return WriteAccess::not_needed;
  auto target = parse_target(header.target());
  if (!target) return WriteAccess::not_needed;  // answered 400 once read
  api::Request probe;
  probe.method = std::string(header.method_string());
  probe.path = std::move(target->path);
  auto match = state_.router.match(probe);
  if (!match.route || match.route->access != api::Access::api_key) return WriteAccess::not_needed;
  std::string_view key = header[http::field::authorization];
  if (key.size() > 7 && beast::iequals(key.substr(0, 7), "Bearer "))
    key.remove_prefix(7);
  else
    key = header["X-API-Key"];
  while (!key.empty() && key.front() == ' ') key.remove_prefix(1);
  while (!key.empty() && key.back() == ' ') key.remove_suffix(1);
  if (key.empty()) return WriteAccess::missing_key;
  if (!state_.verify_api_key) return WriteAccess::bad_key;
  try {
    return state_.verify_api_key(key) ? WriteAccess::granted : WriteAccess::bad_key;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: cannot check an API key: %s\n", e.what());
    return WriteAccess::unavailable;
  }
}

void HttpSession::refuse_write(const RequestFacts& facts) {
  api::Response r;
  if (write_access_ == WriteAccess::unavailable) {
    r = api::error_response(503, "unavailable", "cannot check the API key now; retry shortly");
    r.headers.emplace_back("Retry-After", "1");
  } else if (write_access_ == WriteAccess::bad_key) {
    r = api::error_response(401, "invalid_api_key", "the API key is not valid (unknown, revoked or mistyped)",
                            "Authorization");
    r.headers.emplace_back("WWW-Authenticate", "Bearer realm=\"tourmap\", error=\"invalid_token\"");
  } else {
    r = api::error_response(401, "unauthorized",
                            "this request changes data and needs an API key: send `Authorization: Bearer <key>` "
                            "or `X-API-Key: <key>` (an operator creates keys with `tourmap keys create`)",
                            "Authorization");
    r.headers.emplace_back("WWW-Authenticate", "Bearer realm=\"tourmap\"");
  }
  send(finish_response(std::move(r), facts, state_.config), route_label_);
}

void HttpSession::answer_preflight(const RequestFacts& facts) {
  route_label_ = "preflight";
  if (!state_.cors.allows(origin_))
    return send(finish_response(api::error_response(403, "origin_not_allowed",
                                                    "cross-origin requests from " + origin_ + " are not allowed",
                                                    "Origin"),
                                facts, state_.config),
                route_label_);
  Response res{http::status::no_content, facts.version};
  res.set(http::field::server, "tourmap");
  res.set("X-Content-Type-Options", "nosniff");
  res.set(http::field::access_control_allow_methods, CorsPolicy::kAllowMethods);
  res.set(http::field::access_control_allow_headers, CorsPolicy::kAllowHeaders);
  res.set(http::field::access_control_max_age, std::to_string(CorsPolicy::kMaxAgeS));
  res.keep_alive(facts.keep_alive);
  send(std::move(res), route_label_);  // send() adds Allow-Origin and Vary
}

// With CORS on, every response varies by Origin (a cache must not hand one origin's answer
// to another); an allowed origin gets Access-Control-Allow-Origin (and the headers it may read),
// a refused one nothing.
void HttpSession::add_cors_headers(Response& res) const {
  if (!state_.cors.enabled()) return;
  const std::string vary(res[http::field::vary]);
  res.set(http::field::vary, vary.empty() ? std::string("Origin") : vary + ", Origin");
  if (!state_.cors.allows(origin_)) return;
  res.set(http::field::access_control_allow_origin, origin_);
  res.set(http::field::access_control_expose_headers, CorsPolicy::kExposeHeaders);
  res.set("Timing-Allow-Origin", origin_);  // Server-Timing in the browser's resource timings too
}

void HttpSession::send(Response&& res, const std::string& route_label) {
  route_label_ = route_label;
  add_cors_headers(res);
  bool close = res.need_eof() || state_.stopping;
  if (close) res.keep_alive(false);
  response_ = std::make_shared<Response>(std::move(res));
  // Counted before the write, not after it: a client that has read this response and asks
  // /metrics next must find it counted. The latency is to the response being ready.
  const double ready_s = std::chrono::duration<double>(Clock::now() - started_).count();
  state_.metrics.observe(route_label_, method_, static_cast<int>(response_->result_int()), ready_s);
  stream_.expires_after(seconds(state_.config.request_timeout_s));
  http::async_write(stream_, *response_,
                    [self = shared_from_this(), close](beast::error_code ec, std::size_t bytes) {
                      self->on_write(close, ec, bytes);
                    });
}

void HttpSession::on_write(bool close_after, beast::error_code ec, std::size_t bytes) {
  int status = response_ ? static_cast<int>(response_->result_int()) : 0;
  double ms = std::chrono::duration<double, std::milli>(Clock::now() - started_).count();
  state_.access_log.write(client_, method_, target_, status, bytes, ms);
  if (counted_) --state_.in_flight;
  counted_ = false;
  response_.reset();
  busy_ = false;
  if (!ec && close_after && unread_input_) return linger_close();
  if (ec || close_after) return close();
  read_header();
}

void HttpSession::shutdown_requested() {
  // Idle connections close now; a busy one closes after its response (send() sees `stopping`).
  if (!busy_) close();
}

void HttpSession::close() {
  beast::error_code ec;
  stream_.socket().shutdown(net::ip::tcp::socket::shutdown_both, ec);
  stream_.socket().close(ec);
}

void HttpSession::linger_close() {
  unread_input_ = false;
  beast::error_code ec;
  stream_.socket().shutdown(net::ip::tcp::socket::shutdown_send, ec);  // the client sees our end
  if (ec) return close();
  stream_.expires_after(std::chrono::seconds(kLingerSeconds));
  linger_more();
}

void HttpSession::linger_more() {
  stream_.async_read_some(net::buffer(discard_), [self = shared_from_this()](beast::error_code ec, std::size_t n) {
    self->lingered_ += n;
    if (ec || self->lingered_ >= kLingerBytes) return self->close();  // EOF, timeout or enough
    self->linger_more();
  });
}

}  // namespace tourmap::server
