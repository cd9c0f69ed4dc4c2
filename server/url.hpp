#pragma once
// Request-target parsing: percent-decoding of the path and the query string.

#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace tourmap::server {

// Decodes %XX (and '+' as space when `plus_is_space`); nullopt on a malformed escape or NUL.
std::optional<std::string> percent_decode(std::string_view in, bool plus_is_space);

struct Target {
  std::string path;
  std::map<std::string, std::string> query;
};

// nullopt when the path or query cannot be decoded.
std::optional<Target> parse_target(std::string_view target);

}  // namespace tourmap::server
