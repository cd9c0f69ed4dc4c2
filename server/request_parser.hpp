#pragma once
// The HTTP/1.1 request parser every connection uses: Beast's basic_parser with a string body,
// plus the limits Beast's own http::parser lacks.
//
// Why not http::request_parser: it stores chunked trailer fields into the request's header
// fields without any limit (a trailer of five million fields grew the server by 320 MB), and a
// field longer than 64 KiB makes its field table throw std::length_error out of the parse,
// which nothing in an async read can catch (the process aborted). Here header and trailer
// fields share one count and the trailer one byte budget, trailer fields are counted and then
// dropped (RFC 9110 6.5.1: a recipient may discard them; nothing here reads them), and every
// failure is an error code, never an exception.

#include <boost/beast/http/basic_parser.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>

#include <cstddef>
#include <optional>

namespace tourmap::server {

class RequestParser : public boost::beast::http::basic_parser<true> {
 public:
  using Request = boost::beast::http::request<boost::beast::http::string_body>;

  // max_fields: header fields plus trailer fields; max_trailer_bytes: names, values and
  // separators of all trailer fields. Both refuse with error::header_limit.
  RequestParser(std::size_t max_fields, std::size_t max_trailer_bytes);

  Request& get() { return message_; }
  const Request& get() const { return message_; }
  Request release() { return std::move(message_); }

  std::size_t fields() const { return fields_; }
  std::size_t trailer_bytes() const { return trailer_bytes_; }

 private:
  using error_code = boost::beast::error_code;
  using string_view = boost::beast::string_view;
  using verb = boost::beast::http::verb;
  using field = boost::beast::http::field;

  void on_request_impl(verb method, string_view method_str, string_view target, int version,
                       error_code& ec) override;
  void on_response_impl(int code, string_view reason, int version, error_code& ec) override;
  void on_field_impl(field name, string_view name_string, string_view value, error_code& ec) override;
  void on_header_impl(error_code& ec) override;
  void on_body_init_impl(const boost::optional<std::uint64_t>& content_length, error_code& ec) override;
  std::size_t on_body_impl(string_view body, error_code& ec) override;
  void on_chunk_header_impl(std::uint64_t size, string_view extensions, error_code& ec) override;
  std::size_t on_chunk_body_impl(std::uint64_t remain, string_view body, error_code& ec) override;
  void on_finish_impl(error_code& ec) override;

  std::size_t append_body(string_view body, error_code& ec);

  Request message_;
  std::size_t max_fields_;
  std::size_t max_trailer_bytes_;
  std::size_t fields_ = 0;
  std::size_t trailer_bytes_ = 0;
  bool in_trailer_ = false;  // the header is complete: fields from now on are trailer fields
};

}  // namespace tourmap::server
