// Raw bytes into a real connection: a server::HttpSession (the request parser with its header
// and trailer limits, chunked bodies, Expect: 100-continue, pipelining, WebSocket upgrades,
// routing onto the read and compute pools, response writing) on one end of a socketpair, the
// input written to the other end and its write side shut, then everything the server answers
// read until it closes the connection.
//
// Behind the connection: support/server_world.hpp (a small store, the full route table).
// Findings: a crash or sanitizer report, an exception that reaches the IO thread (counted in
// ServerState::handler_exceptions), a 500 answer, or a connection the server does not close
// within 8 s of the client's end of input (a hang).

#include "fuzz_common.hpp"
#include "support/server_world.hpp"

#include "server/http_session.hpp"

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/strand.hpp>

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <memory>
#include <thread>
#include <vector>

namespace {

using namespace tourmap;
namespace net = boost::asio;

// The world and the IO thread that runs its connections; the thread stops before the world goes.
struct Connections {
  fuzz::ServerWorld world;
  net::executor_work_guard<net::io_context::executor_type> guard{world.ioc.get_executor()};
  std::thread io{[this] { world.ioc.run(); }};

  ~Connections() {
    guard.reset();
    world.ioc.stop();
    io.join();
  }
};

Connections& connections() {
  static Connections c;
  return c;
}

bool write_all(int fd, std::string_view data) {
  while (!data.empty()) {
    const ssize_t n = ::send(fd, data.data(), data.size(), MSG_NOSIGNAL);
    if (n <= 0) return false;  // the server closed early (e.g. after a 431): fine
    data.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

// Reads until the server closes; false on a timeout.
bool read_until_closed(int fd, std::string& out, std::chrono::milliseconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  char buf[16384];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) return true;  // closed (or reset)
    if (out.size() < (1u << 20)) out.append(buf, static_cast<std::size_t>(n));
  }
}

// The status of every response in `answer`, walking status line, header and Content-Length body
// (the server always sends a Content-Length; a WebSocket handshake's 101 ends the walk).
std::vector<int> statuses(const std::string& answer) {
  std::vector<int> out;
  std::size_t at = 0;
  while (at + 12 <= answer.size() && answer.compare(at, 9, "HTTP/1.1 ") == 0) {
    const int status = std::atoi(answer.substr(at + 9, 3).c_str());
    out.push_back(status);
    const auto end = answer.find("\r\n\r\n", at);
    if (end == std::string::npos || status == 101) break;
    std::size_t length = 0;
    const auto cl = answer.find("Content-Length: ", at);
    if (cl != std::string::npos && cl < end) length = std::strtoul(answer.c_str() + cl + 16, nullptr, 10);
    at = end + 4 + length;
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  connections();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Connections& c = connections();
  int sv[2];
  FUZZ_CHECK(::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) == 0);
  net::ip::tcp::socket server_end(net::make_strand(c.world.ioc));
  boost::system::error_code ec;
  server_end.assign(net::ip::tcp::v4(), sv[0], ec);  // a stream socket is all HttpSession reads and writes
  FUZZ_CHECK(!ec);
  net::post(c.world.ioc, [&c, s = std::move(server_end)]() mutable {
    std::make_shared<server::HttpSession>(std::move(s), c.world.state)->run();
  });

  write_all(sv[1], fuzz::as_view(data, size));
  ::shutdown(sv[1], SHUT_WR);
  std::string answer;
  const bool closed = read_until_closed(sv[1], answer, std::chrono::seconds(8));
  ::close(sv[1]);
  FUZZ_CHECK(closed);
  FUZZ_CHECK(c.world.state.handler_exceptions.load() == 0);
  for (int status : statuses(answer)) FUZZ_CHECK(status != 500);  // bad input is a 4xx, overload a 503
  return 0;
}
