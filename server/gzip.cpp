#include "gzip.hpp"

#include <libdeflate.h>
#include <zlib.h>

#include <array>
#include <cctype>
#include <memory>
#include <stdexcept>

namespace tourmap::server {
namespace {

// Bodies are compressed whole (they are in memory already), so libdeflate fits better than
// zlib's streaming deflate: at the same level it is 2-3x faster for a similar size. One
// compressor per thread and level, made on first use: allocating one costs ~0.5 MiB of state.
// zlib stays for decompression (gzip_decompress), which gets streams of unknown size.
struct CompressorDeleter {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};
using Compressor = std::unique_ptr<libdeflate_compressor, CompressorDeleter>;

libdeflate_compressor* compressor_for(int level) {
  thread_local std::array<Compressor, 13> compressors;  // libdeflate's levels 0..12
  if (level < 0 || level > 12) level = 6;                // zlib's Z_DEFAULT_COMPRESSION is 6
  auto& slot = compressors[static_cast<std::size_t>(level)];
  if (!slot) {
    slot.reset(libdeflate_alloc_compressor(level));
    if (!slot) throw std::runtime_error("libdeflate_alloc_compressor failed");
  }
  return slot.get();
}

}  // namespace

std::string gzip_compress(std::string_view data, int level) {
  libdeflate_compressor* c = compressor_for(level);
  std::string out(libdeflate_gzip_compress_bound(c, data.size()), '\0');
  const std::size_t n = libdeflate_gzip_compress(c, data.data(), data.size(), out.data(), out.size());
  if (n == 0) throw std::runtime_error("libdeflate_gzip_compress failed");  // cannot happen: bound
  out.resize(n);
  return out;
}

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
