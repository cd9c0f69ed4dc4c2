// The request parser: Beast's basic_parser plus limits on header and trailer fields, and no
// exception out of a parse (a field beyond 64 KiB used to abort the server).

#include "server/request_parser.hpp"

#include <boost/asio/buffer.hpp>
#include <boost/beast/http/error.hpp>

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace tourmap::server {
namespace {

namespace http = boost::beast::http;

struct Parsed {
  boost::beast::error_code ec;
  bool done = false;
};

// Feeds the whole message in one piece, the way a read that got everything at once does.
Parsed parse(RequestParser& p, const std::string& bytes) {
  p.eager(true);
  p.header_limit(std::numeric_limits<std::uint32_t>::max());
  p.body_limit(std::numeric_limits<std::uint64_t>::max());
  Parsed out;
  std::size_t used = 0;
  while (used < bytes.size() && !p.is_done()) {
    const auto n = p.put(boost::asio::buffer(bytes.data() + used, bytes.size() - used), out.ec);
    if (out.ec) break;
    used += n;
    if (n == 0) break;
  }
  out.done = p.is_done();
  return out;
}

TEST(RequestParser, ParsesARequestWithABody) {
  RequestParser p(100, 1024);
  auto r = parse(p, "POST /api/v1/x?y=1 HTTP/1.1\r\nHost: a\r\nContent-Type: text/plain\r\nContent-Length: 5\r\n\r\nhello");
  ASSERT_FALSE(r.ec) << r.ec.message();
  ASSERT_TRUE(r.done);
  auto req = p.release();
  EXPECT_EQ(req.method(), http::verb::post);
  EXPECT_EQ(req.target(), "/api/v1/x?y=1");
  EXPECT_EQ(req[http::field::content_type], "text/plain");
  EXPECT_EQ(req.body(), "hello");
}

TEST(RequestParser, KeepsUnknownMethods) {
  RequestParser p(100, 1024);
  auto r = parse(p, "FROB /x HTTP/1.1\r\nHost: a\r\n\r\n");
  ASSERT_FALSE(r.ec) << r.ec.message();
  EXPECT_EQ(p.get().method(), http::verb::unknown);
  EXPECT_EQ(p.get().method_string(), "FROB");
}

TEST(RequestParser, ChunkedBodyWithTrailersThatAreCountedAndDropped) {
  RequestParser p(100, 1024);
  auto r = parse(p,
                 "POST /x HTTP/1.1\r\nHost: a\r\nTransfer-Encoding: chunked\r\n\r\n"
                 "3\r\nabc\r\n2\r\nde\r\n0\r\nOrigin: https://evil.example\r\nX-Trailer: 1\r\n\r\n");
  ASSERT_FALSE(r.ec) << r.ec.message();
  ASSERT_TRUE(r.done);
  EXPECT_EQ(p.get().body(), "abcde");
  EXPECT_EQ(p.get().count(http::field::origin), 0u) << "a trailer field reached the request's header";
  EXPECT_EQ(p.get().count("X-Trailer"), 0u);
  EXPECT_GT(p.trailer_bytes(), 0u);
}

TEST(RequestParser, TrailerBeyondItsByteBudgetIsAHeaderLimitError) {
  RequestParser p(1000, 1024);
  std::string trailer;
  for (int i = 0; i < 100; ++i) trailer.append("X-Filler-").append(std::to_string(i)).append(": aaaaaaaaaaaaaaaaaaaa\r\n");
  auto r = parse(p, "GET /healthz HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n" + trailer + "\r\n");
  EXPECT_EQ(r.ec, http::error::header_limit);
}

TEST(RequestParser, FieldCountCoversHeaderAndTrailer) {
  RequestParser p(10, 1 << 20);
  std::string header = "GET / HTTP/1.1\r\n";
  for (int i = 0; i < 11; ++i) header.append("A").append(std::to_string(i)).append(": b\r\n");
  auto r = parse(p, header + "\r\n");
  EXPECT_EQ(r.ec, http::error::header_limit);

  RequestParser q(10, 1 << 20);
  std::string trailer;
  for (int i = 0; i < 9; ++i) trailer.append("T").append(std::to_string(i)).append(": 1\r\n");
  auto t = parse(q, "GET / HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n" + trailer + "\r\n");
  EXPECT_EQ(t.ec, http::error::header_limit) << "2 header + 9 trailer fields passed a limit of 10";
}

// A field longer than Beast's field table holds (64 KiB): an error code, not std::length_error.
TEST(RequestParser, OversizedFieldsAreErrorsNotExceptions) {
  const std::string huge(70000, 'a');
  RequestParser header_field(100, 1 << 20);
  Parsed r;
  EXPECT_NO_THROW(r = parse(header_field, "GET / HTTP/1.1\r\nX: " + huge + "\r\n\r\n"));
  EXPECT_EQ(r.ec, http::error::header_limit);

  RequestParser trailer_field(100, 1 << 20);  // trailer budget above the field's size
  EXPECT_NO_THROW(
      r = parse(trailer_field, "GET / HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n0\r\nX: " + huge + "\r\n\r\n"));
  EXPECT_FALSE(r.ec) << "a trailer within its budget is fine: it is dropped, not stored";
  EXPECT_TRUE(r.done);
}

}  // namespace
}  // namespace tourmap::server
