#include "respond.hpp"

#include "gzip.hpp"

#include "util/hash.hpp"


namespace tourmap::server {
namespace {

bool compressible(const std::string& content_type) {
  return content_type.rfind("application/json", 0) == 0 || content_type.rfind("application/geo+json", 0) == 0 ||
         content_type.rfind("text/", 0) == 0 || content_type.rfind("image/svg+xml", 0) == 0 ||
         content_type.rfind("application/yaml", 0) == 0;
}

bool has_header(const api::Response& r, const char* name) {
  for (const auto& [k, v] : r.headers)
    if (boost::beast::iequals(k, name)) return true;
  return false;
}

}  // namespace

std::string weak_etag(const std::string& body) { return "W/\"" + util::hex64(util::fnv1a64(body)) + "\""; }

bool etag_matches(const std::string& header, const std::string& etag) {
  if (header.empty()) return false;
  if (header == "*") return true;
  // Weak comparison: W/"x" matches "x" and W/"x".
  auto strip = [](std::string s) { return s.rfind("W/", 0) == 0 ? s.substr(2) : s; };
  auto want = strip(etag);
  std::size_t pos = 0;
  while (pos < header.size()) {
    auto comma = header.find(',', pos);
    auto item = header.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    pos = comma == std::string::npos ? header.size() : comma + 1;
    auto b = item.find_first_not_of(' '), e = item.find_last_not_of(' ');
    if (b == std::string::npos) continue;
    if (strip(item.substr(b, e - b + 1)) == want) return true;
  }
  return false;
}

http::response<http::string_body> finish_response(api::Response r, const RequestFacts& facts, const Config& config) {
  http::response<http::string_body> res{static_cast<http::status>(r.status), facts.version};
  res.set(http::field::server, "tourmap");
  res.set(http::field::content_type, r.content_type);
  res.set("X-Content-Type-Options", "nosniff");
  for (const auto& [k, v] : r.headers) res.set(k, v);

  bool ok_get = r.status == 200 && (facts.method == http::verb::get || facts.method == http::verb::head);
  if (r.cacheable && ok_get) {
    auto etag = weak_etag(r.body);
    res.set(http::field::etag, etag);
    if (!has_header(r, "Cache-Control"))
      res.set(http::field::cache_control, r.max_age_s > 0 ? "public, max-age=" + std::to_string(r.max_age_s)
                                                          : std::string("no-cache"));
    if (etag_matches(facts.if_none_match, etag)) {
      res.result(http::status::not_modified);
      res.erase(http::field::content_type);
      res.keep_alive(facts.keep_alive);
      return res;  // 304: no body, no Content-Length
    }
  } else if (!has_header(r, "Cache-Control")) {
    res.set(http::field::cache_control, "no-store");
  }

  if (compressible(r.content_type)) {
    res.set(http::field::vary, "Accept-Encoding");
    if (r.body.size() >= config.gzip_min_bytes && accepts_gzip(facts.accept_encoding)) {
      // Big bodies (deformed networks, whole road networks) get the fastest level: on a drag
      // loop the compression time matters more than the last 10% of bytes.
      r.body = gzip_compress(r.body, r.body.size() > (256u << 10) ? 1 : 5);
      res.set(http::field::content_encoding, "gzip");
    }
  }
  res.body() = std::move(r.body);
  res.keep_alive(facts.keep_alive);
  res.prepare_payload();
  if (facts.method == http::verb::head) res.body().clear();  // Content-Length stays that of GET
  return res;
}

}  // namespace tourmap::server
