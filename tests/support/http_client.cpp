#include "http_client.hpp"

#include <thread>

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <cctype>
#include <functional>
#include <stdexcept>

namespace tourmap::test {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;

HttpResult http_request(unsigned short port, const std::string& method, const std::string& raw_target,
                        const std::map<std::string, std::string>& headers, const std::string& body) {
  net::io_context ioc;
  beast::tcp_stream stream(ioc);
  stream.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
  stream.expires_after(std::chrono::seconds(60));
  http::request<http::string_body> req{http::string_to_verb(method), raw_target, 11};
  req.set(http::field::host, "127.0.0.1");
  for (const auto& [k, v] : headers) req.set(k, v);
  req.body() = body;
  if (!body.empty() || method == "POST") req.prepare_payload();
  http::write(stream, req);

  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.body_limit(256u << 20);
  if (method == "HEAD") parser.skip(true);
  // Asynchronously, so that the stream's timeout applies: a server that never answers fails the
  // test naming the request instead of hanging it until ctest kills it.
  beast::error_code read_error;
  http::async_read(stream, buffer, parser, [&](beast::error_code e, std::size_t) { read_error = e; });
  ioc.run();
  if (read_error) throw std::runtime_error(method + " " + raw_target + ": no answer (" + read_error.message() + ")");
  auto res = parser.release();
  HttpResult out;
  out.status = static_cast<int>(res.result_int());
  for (const auto& field : res) {
    std::string name(field.name_string());
    for (auto& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    out.headers[name] = std::string(field.value());
  }
  out.body = std::move(res.body());
  beast::error_code ec;
  stream.socket().shutdown(tcp::socket::shutdown_both, ec);
  return out;
}

std::string raw_exchange(unsigned short port, const std::string& bytes, std::chrono::milliseconds timeout) {
  net::io_context ioc;
  beast::tcp_stream stream(ioc);
  stream.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
  beast::error_code ec;
  net::write(stream, net::buffer(bytes), ec);
  std::string out;
  if (ec) return out;
  // Asynchronous reads: the stream's timeout applies only to those (a blocking read_some would
  // wait for the server however long it keeps the connection open).
  stream.expires_after(timeout);
  char buf[4096];
  std::function<void()> read_more = [&] {
    stream.async_read_some(net::buffer(buf), [&](beast::error_code read_ec, std::size_t n) {
      out.append(buf, n);
      if (!read_ec) read_more();
    });
  };
  read_more();
  ioc.run();
  return out;
}

struct WsClient::Impl {
  net::io_context ioc;
  beast::websocket::stream<beast::tcp_stream> ws{ioc};
};

WsClient::WsClient(unsigned short port, const std::string& path) : impl_(std::make_unique<Impl>()) {
  beast::get_lowest_layer(impl_->ws).connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
  impl_->ws.handshake("127.0.0.1:" + std::to_string(port), path);
}

WsClient::~WsClient() {
  beast::error_code ec;
  impl_->ws.close(beast::websocket::close_code::normal, ec);
}

void WsClient::send(const std::string& text) {
  impl_->ws.text(true);
  impl_->ws.write(net::buffer(text));
}

// Beast's stream timeouts apply to asynchronous operations only: read asynchronously and run
// the io_context until the message or the timeout (which closes the connection) arrives.
WsClient::Message WsClient::receive_message(std::chrono::milliseconds timeout) {
  beast::get_lowest_layer(impl_->ws).expires_after(timeout);
  beast::flat_buffer buffer;
  beast::error_code ec;
  impl_->ws.async_read(buffer, [&ec](beast::error_code e, std::size_t) { ec = e; });
  impl_->ioc.restart();
  impl_->ioc.run();
  beast::get_lowest_layer(impl_->ws).expires_never();
  if (ec) throw beast::system_error(ec);
  return {!impl_->ws.got_text(), beast::buffers_to_string(buffer.data())};
}

std::string WsClient::receive(std::chrono::milliseconds timeout) { return receive_message(timeout).data; }

int WsClient::close_code() const { return static_cast<int>(impl_->ws.reason().code); }

void WsClient::pause(std::chrono::milliseconds how_long) { std::this_thread::sleep_for(how_long); }

}  // namespace tourmap::test
