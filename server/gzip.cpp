#include "gzip.hpp"

#include <zlib.h>

#include <array>
#include <cctype>
#include <memory>
#include <stdexcept>

namespace tourmap::server {
namespace {

// A deflate stream kept per thread and level: deflateInit2 allocates and clears ~256 KiB
// (window, hash chains, pending buffer), which under the cluster load showed up as malloc, free
// and malloc_consolidate next to deflate itself; deflateReset only clears the hash heads.
// (Windows sized to the body, for a smaller state, measured no faster.)
class Deflater {
 public:
  explicit Deflater(int level) {
    // windowBits 15 + 16: gzip wrapper instead of zlib's.
    if (deflateInit2(&zs_, level, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
      throw std::runtime_error("deflateInit2 failed");
  }
  ~Deflater() { deflateEnd(&zs_); }
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;

  std::string compress(std::string_view data) {
    if (deflateReset(&zs_) != Z_OK) throw std::runtime_error("deflateReset failed");
    std::string out(deflateBound(&zs_, data.size()), '\0');
    zs_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
    zs_.avail_in = static_cast<uInt>(data.size());
    zs_.next_out = reinterpret_cast<Bytef*>(out.data());
    zs_.avail_out = static_cast<uInt>(out.size());
    const int rc = deflate(&zs_, Z_FINISH);
    if (rc != Z_STREAM_END) throw std::runtime_error("deflate failed");
    out.resize(zs_.total_out);
    return out;
  }

 private:
  z_stream zs_{};
};

Deflater& deflater_for(int level) {
  // Levels 0..9 (Z_DEFAULT_COMPRESSION, -1, is 6); made on first use in each thread.
  thread_local std::array<std::unique_ptr<Deflater>, 10> streams;
  if (level < 0 || level > 9) level = 6;
  auto& slot = streams[static_cast<std::size_t>(level)];
  if (!slot) slot = std::make_unique<Deflater>(level);
  return *slot;
}

}  // namespace

std::string gzip_compress(std::string_view data, int level) { return deflater_for(level).compress(data); }

std::string gzip_decompress(std::string_view data) {
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 16) != Z_OK) throw std::runtime_error("inflateInit2 failed");
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = static_cast<uInt>(data.size());
  std::string out;
  char buf[65536];
  int rc = Z_OK;
  while (rc != Z_STREAM_END) {
    zs.next_out = reinterpret_cast<Bytef*>(buf);
    zs.avail_out = sizeof buf;
    rc = inflate(&zs, Z_NO_FLUSH);
    if (rc != Z_OK && rc != Z_STREAM_END) {
      inflateEnd(&zs);
      throw std::runtime_error("inflate failed");
    }
    out.append(buf, sizeof buf - zs.avail_out);
  }
  inflateEnd(&zs);
  return out;
}

bool accepts_gzip(std::string_view header) {
  // Comma-separated codings with optional ;q=; gzip is refused only by q=0.
  std::size_t pos = 0;
  while (pos < header.size()) {
    auto comma = header.find(',', pos);
    auto item = header.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos);
    pos = comma == std::string_view::npos ? header.size() : comma + 1;
    while (!item.empty() && std::isspace(static_cast<unsigned char>(item.front()))) item.remove_prefix(1);
    auto semi = item.find(';');
    auto coding = item.substr(0, semi);
    while (!coding.empty() && std::isspace(static_cast<unsigned char>(coding.back()))) coding.remove_suffix(1);
    if (coding != "gzip" && coding != "*") continue;
    if (semi == std::string_view::npos) return true;
    auto q = item.find("q=", semi);
    if (q == std::string_view::npos) return true;
    auto value = item.substr(q + 2);
    bool zero = !value.empty() && value[0] == '0';
    for (char c : value.substr(1)) zero = zero && (c == '.' || c == '0' || std::isspace(static_cast<unsigned char>(c)));
    return !zero;
  }
  return false;
}

}  // namespace tourmap::server
