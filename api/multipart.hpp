#pragma once
// multipart/form-data bodies (RFC 7578), for uploads of several files in one request
// (PUT /cities/{id}/source: an OSM extract and a GTFS feed). Boost.Beast parses HTTP but not
// multipart bodies, and Debian has no small multipart library, so this is a few lines over
// the body already in memory: parts are views into it, nothing is copied.
//
// Bounded: at most kMaxMultipartParts parts, part headers of at most 4 KiB each. Throws
// ApiError 400 (field "body") naming what is wrong: no boundary, a part without a name, a
// missing closing delimiter.

#include "http.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace tourmap::api {

inline constexpr std::size_t kMaxMultipartParts = 8;

struct MultipartPart {
  std::string name;      // Content-Disposition name
  std::string filename;  // Content-Disposition filename ("" when absent)
  std::string_view data;  // the part's bytes, a view into the body
};

// True when `content_type` is multipart/form-data.
bool is_multipart(std::string_view content_type);

// The parts of `body`, whose Content-Type header is `content_type` (it carries the boundary).
std::vector<MultipartPart> parse_multipart(std::string_view body, std::string_view content_type);

}  // namespace tourmap::api
