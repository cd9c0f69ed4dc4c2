#include "respond.hpp"

#include "gzip.hpp"

#include "util/hash.hpp"

#include <cstdint>
#include <cstring>

namespace tourmap::server {
namespace {

// The ETag's hash, 8 bytes per step: FNV-1a's one multiply per byte took ~2.5 % of the server's
// time under the cluster load (7 KB bodies). Stable across builds and runs; not for security.
std::uint64_t body_hash(std::string_view s) {
  constexpr std::uint64_t kMul = 0x9e3779b97f4a7c15ull;
  auto mix = [](std::uint64_t h) {  // murmur3's finaliser: every input bit reaches every output bit
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    return h ^ (h >> 33);
  };
  std::uint64_t h = util::kFnvOffset ^ (s.size() * kMul);
  std::size_t i = 0;
  for (; i + 8 <= s.size(); i += 8) {
    std::uint64_t word;
    std::memcpy(&word, s.data() + i, 8);
    h = (h ^ word) * kMul;
    h ^= h >> 29;
  }
  std::uint64_t tail = 0;
  if (i < s.size()) std::memcpy(&tail, s.data() + i, s.size() - i);
  return mix(h ^ tail);
}

// Big bodies (deformed networks, whole road networks) get the fastest level: on a drag loop the
// compression time matters more than the last 10 % of bytes. So do small ones (cluster answers,
// city summaries): for a 7 KB cluster answer level 5 saves ~110 of ~1800 bytes (less than a
// TCP segment) for ~40 % more deflate time, and deflate was a third of such a request's CPU.
int gzip_level(std::size_t bytes) { return bytes > (256u << 10) || bytes < (16u << 10) ? 1 : 5; }

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

std::string weak_etag(const std::string& body) { return "W/\"" + util::hex64(body_hash(body)) + "\""; }

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
      r.body = gzip_compress(r.body, gzip_level(r.body.size()));
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
