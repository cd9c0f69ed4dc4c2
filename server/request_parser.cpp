#include "request_parser.hpp"

#include <boost/beast/http/error.hpp>

#include <new>
#include <stdexcept>

namespace tourmap::server {

namespace http = boost::beast::http;

RequestParser::RequestParser(std::size_t max_fields, std::size_t max_trailer_bytes)
    : max_fields_(max_fields), max_trailer_bytes_(max_trailer_bytes) {}

void RequestParser::on_request_impl(verb method, string_view method_str, string_view target, int version,
                                    error_code& ec) {
  try {
    message_.target(target);
    if (method != verb::unknown)
      message_.method(method);
    else
      message_.method_string(method_str);
    message_.version(version);
  } catch (const std::exception&) {  // std::length_error, std::bad_alloc
    ec = http::error::header_limit;
  }
}

void RequestParser::on_response_impl(int, string_view, int, error_code& ec) {
  ec = http::error::bad_version;  // a request parser never sees a status line
}

void RequestParser::on_field_impl(field name, string_view name_string, string_view value, error_code& ec) {
  if (++fields_ > max_fields_) {
    ec = http::error::header_limit;
    return;
  }
  if (in_trailer_) {
    trailer_bytes_ += name_string.size() + value.size() + 4;  // ": " and CRLF
    if (trailer_bytes_ > max_trailer_bytes_) ec = http::error::header_limit;
    return;  // counted, then dropped
  }
  try {
    message_.insert(name, name_string, value);
  } catch (const std::exception&) {  // a name or value longer than the field table allows (64 KiB)
    ec = http::error::header_limit;
  }
}

void RequestParser::on_header_impl(error_code& ec) {
  in_trailer_ = true;
  ec = {};
}

void RequestParser::on_body_init_impl(const boost::optional<std::uint64_t>& content_length, error_code& ec) {
  ec = {};
  if (!content_length) return;
  try {
    message_.body().reserve(static_cast<std::size_t>(*content_length));  // within body_limit (checked before)
  } catch (const std::exception&) {
    ec = http::error::buffer_overflow;
  }
}

std::size_t RequestParser::append_body(string_view body, error_code& ec) {
  try {
    message_.body().append(body.data(), body.size());
  } catch (const std::exception&) {
    ec = http::error::buffer_overflow;
    return 0;
  }
  ec = {};
  return body.size();
}

std::size_t RequestParser::on_body_impl(string_view body, error_code& ec) { return append_body(body, ec); }

void RequestParser::on_chunk_header_impl(std::uint64_t, string_view, error_code& ec) { ec = {}; }

std::size_t RequestParser::on_chunk_body_impl(std::uint64_t, string_view body, error_code& ec) {
  return append_body(body, ec);
}

void RequestParser::on_finish_impl(error_code& ec) { ec = {}; }

}  // namespace tourmap::server
