#pragma once
// gzip (RFC 1952) through zlib, for JSON/GeoJSON bodies when the client accepts it.

#include <string>
#include <string_view>

namespace tourmap::server {

// Reuses a deflate stream per thread and level (see gzip.cpp): ~256 KiB each, two levels per
// thread with finish_response.
std::string gzip_compress(std::string_view data, int level = 5);
// For tests: the inverse.
std::string gzip_decompress(std::string_view data);

// True when an Accept-Encoding header value allows gzip (q > 0).
bool accepts_gzip(std::string_view accept_encoding);

}  // namespace tourmap::server
