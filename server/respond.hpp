#pragma once
// Turns a handler's api::Response into the HTTP response sent: ETag and 304 for cacheable
// reads, gzip when the client accepts it, caching and security headers, HEAD without a body.

#include "config.hpp"

#include "api/http.hpp"

#include <boost/beast/http.hpp>

#include <string>

namespace tourmap::server {

namespace http = boost::beast::http;

// What finishing a response needs to know about its request.
struct RequestFacts {
  http::verb method = http::verb::get;
  unsigned version = 11;
  bool keep_alive = true;
  std::string accept_encoding;
  std::string if_none_match;
};

http::response<http::string_body> finish_response(api::Response r, const RequestFacts& facts, const Config& config);

// A 64-bit hash of the body (8 bytes per step), as a weak ETag value W/"...".
std::string weak_etag(const std::string& body);
// True when the If-None-Match header value lists `etag` (or is "*").
bool etag_matches(const std::string& if_none_match, const std::string& etag);

}  // namespace tourmap::server
