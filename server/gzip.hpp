#pragma once
// gzip (RFC 1952) for JSON/GeoJSON bodies when the client accepts it: libdeflate compresses,
// zlib decompresses.

#include <string>
#include <string_view>

namespace tourmap::server {

// Levels 1 (fastest) .. 12 (smallest); others mean 6. Keeps one compressor per thread and level
// (see gzip.cpp): two levels per thread with finish_response.
std::string gzip_compress(std::string_view data, int level = 5);
// For tests: the inverse.
std::string gzip_decompress(std::string_view data);

// True when an Accept-Encoding header value allows gzip (q > 0).
bool accepts_gzip(std::string_view accept_encoding);

}  // namespace tourmap::server
