#include "multipart.hpp"

#include "params.hpp"

#include <algorithm>
#include <cctype>

namespace tourmap::api {
namespace {

constexpr std::size_t kMaxPartHeaderBytes = 4096;

std::string lower(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// The value of `key=` in a header's parameters (`; key="value"` or `; key=value`), "" if absent.
std::string header_param(std::string_view header, std::string_view key) {
  const auto low = lower(header);
  for (std::size_t at = low.find(';'); at != std::string::npos; at = low.find(';', at + 1)) {
    auto start = low.find_first_not_of(" \t", at + 1);
    if (start == std::string::npos) break;
    if (low.compare(start, key.size(), key) != 0 || start + key.size() >= low.size() || low[start + key.size()] != '=')
      continue;
    auto value = start + key.size() + 1;
    if (value < header.size() && header[value] == '"') {
      auto end = header.find('"', value + 1);
      if (end == std::string_view::npos) throw bad("body", "unterminated quoted " + std::string(key) + " in a multipart header", "invalid_body");
      return std::string(header.substr(value + 1, end - value - 1));
    }
    auto end = header.find_first_of("; \t", value);
    return std::string(header.substr(value, end == std::string_view::npos ? std::string_view::npos : end - value));
  }
  return "";
}

MultipartPart parse_part(std::string_view part, std::size_t index) {
  const auto where = "body: multipart part " + std::to_string(index + 1);
  const auto end = part.find("\r\n\r\n");
  if (end == std::string_view::npos || end > kMaxPartHeaderBytes)
    throw bad("body", where + ": no header block of at most 4096 bytes", "invalid_body");
  MultipartPart out;
  out.data = part.substr(end + 4);
  const auto headers = part.substr(0, end);
  for (std::size_t start = 0; start <= headers.size();) {
    auto eol = headers.find("\r\n", start);
    const auto line = headers.substr(start, eol == std::string_view::npos ? std::string_view::npos : eol - start);
    if (lower(line.substr(0, 20)) == "content-disposition:") {
      out.name = header_param(line, "name");
      out.filename = header_param(line, "filename");
    }
    if (eol == std::string_view::npos) break;
    start = eol + 2;
  }
  if (out.name.empty()) throw bad("body", where + ": no Content-Disposition name", "invalid_body");
  return out;
}

}  // namespace

bool is_multipart(std::string_view content_type) { return lower(content_type.substr(0, 19)) == "multipart/form-data"; }

std::vector<MultipartPart> parse_multipart(std::string_view body, std::string_view content_type) {
  const auto boundary = header_param(content_type, "boundary");
  if (boundary.empty() || boundary.size() > 70)
    throw bad("body", "multipart/form-data without a boundary of 1 to 70 characters", "invalid_body");
  const std::string delimiter = "--" + boundary;
  // The first delimiter starts the body (or a line of it, after a preamble).
  std::size_t at = body.rfind(delimiter, 0) == 0 ? 0 : body.find("\r\n" + delimiter);
  if (at == std::string_view::npos) throw bad("body", "multipart body without its boundary", "invalid_body");
  if (at != 0) at += 2;
  std::vector<MultipartPart> parts;
  const std::string next = "\r\n" + delimiter;
  for (;;) {
    at += delimiter.size();
    if (body.substr(at, 2) == "--") return parts;  // the closing delimiter
    if (body.substr(at, 2) != "\r\n") throw bad("body", "malformed multipart delimiter line", "invalid_body");
    at += 2;
    const auto end = body.find(next, at);
    if (end == std::string_view::npos) throw bad("body", "multipart body without its closing boundary", "invalid_body");
    if (parts.size() == kMaxMultipartParts)
      throw bad("body", "more than " + std::to_string(kMaxMultipartParts) + " multipart parts", "invalid_body");
    parts.push_back(parse_part(body.substr(at, end - at), parts.size()));
    at = end + 2;
  }
}

}  // namespace tourmap::api
