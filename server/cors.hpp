#pragma once
// Cross-origin requests: an allow-list of origins (`--cors-origins`). Responses to an allowed
// Origin carry Access-Control-Allow-Origin with that origin; preflights (OPTIONS with
// Access-Control-Request-Method) from it are answered 204 with the methods and headers below.
// An empty list turns CORS off: no CORS headers at all, OPTIONS is routed like any method.

#include <string>
#include <string_view>
#include <vector>

namespace tourmap::server {

class CorsPolicy {
 public:
  static constexpr const char* kAllowMethods = "GET, POST, PUT, DELETE, OPTIONS";
  static constexpr const char* kAllowHeaders = "Content-Type, Authorization, X-API-Key, If-None-Match";
  // Response headers a cross-origin script may read besides the safelisted ones.
  static constexpr const char* kExposeHeaders = "ETag, Retry-After, Server-Timing, X-Result-Cache";
  static constexpr int kMaxAgeS = 600;

  // Comma-separated origins, e.g. "https://maps.example.org, http://localhost:5173", or "*"
  // for any origin (except the opaque origin "null"). Case and a trailing '/' do not matter.
  // Throws std::invalid_argument for an entry that is neither "*" nor scheme://host[:port].
  explicit CorsPolicy(std::string_view origins = {});

  bool enabled() const { return any_ || !origins_.empty(); }
  // True when a request with this Origin header value gets CORS headers.
  bool allows(std::string_view origin) const;

 private:
  bool any_ = false;
  std::vector<std::string> origins_;  // normalized: lower case, no trailing '/'
};

}  // namespace tourmap::server
