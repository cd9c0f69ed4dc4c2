#include "load/osm_input.hpp"

#include "load/file.hpp"
#include "load/import_limits.hpp"
#include "load/load_error.hpp"
#include "util/stop.hpp"

#include <bzlib.h>
#include <fcntl.h>
#include <osmium/osm/tag.hpp>
#include <osmium/osm/way.hpp>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

namespace tourmap::load {
namespace {

constexpr std::size_t kChunk = 1 << 20;  // bytes read, and written, at a time

// The compressed input, read in chunks, with look-ahead for the magic bytes of a next member.
class InputBuffer {
 public:
  InputBuffer(const std::string& path, const std::string& source)
      : in_(path, std::ios::binary), source_(source), buf_(kChunk) {
    if (!in_) throw LoadError(source_, std::string("cannot open: ") + std::strerror(errno));
  }
  const unsigned char* data() const { return buf_.data() + begin_; }
  std::size_t avail() const { return end_ - begin_; }
  void consume(std::size_t n) { begin_ += n; }
  // Reads until at least `need` bytes are available or the file ends.
  void fill(std::size_t need) {
    need = std::min(need, buf_.size());
    while (!eof_ && avail() < need) {
      if (begin_ > 0) {
        std::memmove(buf_.data(), buf_.data() + begin_, avail());
        end_ -= begin_;
        begin_ = 0;
      }
      in_.read(reinterpret_cast<char*>(buf_.data() + end_), static_cast<std::streamsize>(buf_.size() - end_));
      const auto got = in_.gcount();
      if (in_.bad()) throw LoadError(source_, "cannot read OSM data: read failed");
      if (got <= 0) eof_ = true;
      end_ += static_cast<std::size_t>(got);
    }
  }
  bool eof() const { return eof_ && avail() == 0; }

 private:
  std::ifstream in_;
  const std::string& source_;
  std::vector<unsigned char> buf_;
  std::size_t begin_ = 0, end_ = 0;
  bool eof_ = false;
};

// Counts and writes decompressed output, enforcing the byte limit.
class Output {
 public:
  Output(SpoolFile& out, std::uint64_t max_bytes, const std::string& source)
      : out_(out), max_(max_bytes), source_(source), buf_(kChunk) {}
  char* data() { return buf_.data(); }
  std::size_t capacity() const { return buf_.size(); }
  std::uint64_t total() const { return total_; }
  void emit(std::size_t n) {
    if (n == 0) return;
    total_ += n;
    if (total_ > max_)
      throw LimitExceeded(source_,
                          "more than " + std::to_string(max_) +
                              " bytes of OSM data after decompression (a large region is best imported as .osm.pbf)",
                          "max_osm_decompressed_bytes", max_);
    out_.write(buf_.data(), n);
  }
  [[noreturn]] void corrupt(const std::string& what) const {
    throw LoadError(source_ + " after " + std::to_string(total_) + " decompressed bytes",
                    "cannot read OSM data: " + what);
  }

 private:
  SpoolFile& out_;
  std::uint64_t max_;
  const std::string& source_;
  std::vector<char> buf_;
  std::uint64_t total_ = 0;
};

std::uint64_t inflate_gzip(InputBuffer& in, Output& out) {
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 16) != Z_OK) out.corrupt("cannot initialise zlib");  // 16: gzip wrapper
  struct End {
    z_stream& zs;
    ~End() { inflateEnd(&zs); }
  } end{zs};
  bool in_member = true;
  for (;;) {
    util::check_stop();
    if (!in_member) {
      in.fill(2);
      // The end, or bytes after the last member that start no other: done (as gzread).
      if (in.avail() < 2 || in.data()[0] != 0x1f || in.data()[1] != 0x8b) break;
      inflateReset(&zs);
      in_member = true;
    }
    in.fill(1);
    if (in.avail() == 0) out.corrupt("truncated gzip data");
    const auto avail = static_cast<uInt>(std::min<std::size_t>(in.avail(), kChunk));
    zs.next_in = const_cast<Bytef*>(in.data());
    zs.avail_in = avail;
    zs.next_out = reinterpret_cast<Bytef*>(out.data());
    zs.avail_out = static_cast<uInt>(out.capacity());
    const int ret = inflate(&zs, Z_NO_FLUSH);
    in.consume(avail - zs.avail_in);
    out.emit(out.capacity() - zs.avail_out);
    if (ret == Z_STREAM_END) {
      in_member = false;
    } else if (ret == Z_BUF_ERROR) {
      // No progress (zlib wants more input than is buffered): read more, or it is truncated.
      const auto before = in.avail();
      in.fill(before + 1);
      if (in.avail() == before) out.corrupt("truncated gzip data");
    } else if (ret != Z_OK) {
      out.corrupt(std::string("corrupt gzip data (") + (zs.msg ? zs.msg : "zlib error " + std::to_string(ret)) + ")");
    }
  }
  return out.total();
}

std::uint64_t decompress_bzip2(InputBuffer& in, Output& out) {
  bz_stream bs{};
  if (BZ2_bzDecompressInit(&bs, 0, 0) != BZ_OK) out.corrupt("cannot initialise bzip2");
  struct End {
    bz_stream& bs;
    ~End() { BZ2_bzDecompressEnd(&bs); }
  } end{bs};
  bool in_stream = true;
  for (;;) {
    util::check_stop();
    if (!in_stream) {
      in.fill(3);
      if (in.avail() < 3 || std::memcmp(in.data(), "BZh", 3) != 0) break;  // the end, or trailing bytes
      BZ2_bzDecompressEnd(&bs);
      bs = bz_stream{};
      if (BZ2_bzDecompressInit(&bs, 0, 0) != BZ_OK) out.corrupt("cannot initialise bzip2");
      in_stream = true;
    }
    in.fill(1);
    if (in.avail() == 0) out.corrupt("truncated bzip2 data");
    const auto avail = static_cast<unsigned>(std::min<std::size_t>(in.avail(), kChunk));
    bs.next_in = const_cast<char*>(reinterpret_cast<const char*>(in.data()));
    bs.avail_in = avail;
    bs.next_out = out.data();
    bs.avail_out = static_cast<unsigned>(out.capacity());
    const int ret = BZ2_bzDecompress(&bs);
    in.consume(avail - bs.avail_in);
    out.emit(out.capacity() - bs.avail_out);
    if (ret == BZ_STREAM_END) {
      in_stream = false;
    } else if (ret != BZ_OK) {
      out.corrupt("corrupt bzip2 data (bzip2 error " + std::to_string(ret) + ")");
    }
  }
  return out.total();
}

// --- a minimal protobuf reader for the PBF framing ---

bool read_varint(std::string_view& s, std::uint64_t& value) {
  value = 0;
  for (int shift = 0; shift < 64 && !s.empty(); shift += 7) {
    const auto b = static_cast<unsigned char>(s.front());
    s.remove_prefix(1);
    value |= std::uint64_t{b & 0x7fu} << shift;
    if (!(b & 0x80)) return true;
  }
  return false;
}

// Calls f(field, wire_type, varint value, length-delimited bytes) for each field of `msg`;
// false on malformed input.
template <class F>
bool for_each_field(std::string_view msg, F&& f) {
  while (!msg.empty()) {
    std::uint64_t key = 0, value = 0;
    if (!read_varint(msg, key)) return false;
    const auto field = key >> 3;
    std::string_view bytes;
    switch (key & 7) {
      case 0:
        if (!read_varint(msg, value)) return false;
        break;
      case 1:
        if (msg.size() < 8) return false;
        msg.remove_prefix(8);
        break;
      case 2:
        if (!read_varint(msg, value) || value > msg.size()) return false;
        bytes = msg.substr(0, value);
        msg.remove_prefix(value);
        break;
      case 5:
        if (msg.size() < 4) return false;
        msg.remove_prefix(4);
        break;
      default:
        return false;
    }
    f(field, key & 7, value, bytes);
  }
  return true;
}

}  // namespace

// --- SpoolFile ---

SpoolFile::SpoolFile() {
  std::error_code ec;
  auto dir = std::filesystem::temp_directory_path(ec);
  if (ec) dir = "/tmp";
  std::string name = (dir / "tourmap-osm-XXXXXX").string();
  fd_ = ::mkostemp(name.data(), O_CLOEXEC);
  if (fd_ < 0) throw LoadError(name, std::string("cannot create a temporary file: ") + std::strerror(errno));
  const std::string proc = "/proc/self/fd/" + std::to_string(fd_);
  if (::access(proc.c_str(), F_OK) == 0) {
    ::unlink(name.c_str());  // reopened through /proc from now on: nothing to clean up later
    path_ = proc;
  } else {
    name_ = name;
    path_ = name;
  }
}

SpoolFile::~SpoolFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!name_.empty()) ::unlink(name_.c_str());
}

void SpoolFile::write(const char* data, std::size_t size) {
  while (size > 0) {
    const auto n = ::write(fd_, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw LoadError("temporary file", std::string("cannot write decompressed OSM data: ") + std::strerror(errno));
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

// --- decompression ---

std::uint64_t decompress_osm(const std::string& path, OsmCompression compression, SpoolFile& out,
                             std::uint64_t max_bytes, const std::string& source) {
  InputBuffer in(path, source);
  Output output(out, max_bytes, source);
  switch (compression) {
    case OsmCompression::gzip: return inflate_gzip(in, output);
    case OsmCompression::bzip2: return decompress_bzip2(in, output);
    case OsmCompression::none: break;
  }
  for (;;) {  // a plain copy, with the same limit
    util::check_stop();
    in.fill(kChunk);
    if (in.avail() == 0) return output.total();
    const auto n = std::min(in.avail(), output.capacity());
    std::memcpy(output.data(), in.data(), n);
    in.consume(n);
    output.emit(n);
  }
}

bool starts_like_gzip(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[2] = {0, 0};
  in.read(reinterpret_cast<char*>(magic), 2);
  return in.gcount() == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
}

// --- PBF framing ---

PbfBlobs scan_pbf_blobs(std::string_view pbf, std::size_t max_blobs, std::uint64_t max_raw_bytes) {
  PbfBlobs blobs;
  while (pbf.size() >= 4 && blobs.count <= max_blobs && blobs.raw_bytes <= max_raw_bytes) {
    const auto* p = reinterpret_cast<const unsigned char*>(pbf.data());
    const std::uint64_t header_size = std::uint64_t{p[0]} << 24 | std::uint64_t{p[1]} << 16 | std::uint64_t{p[2]} << 8 | p[3];
    pbf.remove_prefix(4);
    if (header_size > pbf.size()) break;
    std::uint64_t data_size = 0;
    if (!for_each_field(pbf.substr(0, header_size), [&](std::uint64_t field, std::uint64_t type, std::uint64_t value,
                                                        std::string_view) {
          if (field == 3 && type == 0) data_size = value;  // BlobHeader.datasize
        }))
      break;
    pbf.remove_prefix(header_size);
    if (data_size > pbf.size()) break;
    std::uint64_t raw = 0;
    if (!for_each_field(pbf.substr(0, data_size), [&](std::uint64_t field, std::uint64_t type, std::uint64_t value,
                                                      std::string_view bytes) {
          if (field == 1 && type == 2) raw += bytes.size();             // Blob.raw
          if (field == 2 && type == 0) raw += value & 0xffffffffu;      // Blob.raw_size (int32)
        }))
      break;
    pbf.remove_prefix(data_size);
    ++blobs.count;
    blobs.raw_bytes += raw;
  }
  return blobs;
}

namespace {

// Checks a PBF's blobs before libosmium decodes them (it bounds each blob, not their number).
std::uint64_t check_pbf(std::string_view pbf, const ImportLimits& limits, const std::string& source) {
  const auto blobs = scan_pbf_blobs(pbf, limits.max_osm_pbf_blobs, limits.max_osm_decompressed_bytes);
  check_limit(blobs.count, limits.max_osm_pbf_blobs, "max_osm_pbf_blobs", source, "PBF blobs");
  check_limit(blobs.raw_bytes, limits.max_osm_decompressed_bytes, "max_osm_decompressed_bytes", source,
              "bytes of OSM data after decompression (the sum of the PBF blobs' sizes)");
  return blobs.raw_bytes;
}

// The libosmium format of the (decompressed) text of an extract.
std::string plain_format(const osmium::io::File& file, const std::string& source) {
  switch (file.format()) {
    case osmium::io::file_format::xml: return "osm";
    case osmium::io::file_format::opl: return "opl";
    case osmium::io::file_format::o5m: return "o5m";
    default: throw LoadError(source, "unsupported OSM format (expected .osm, .osm.gz, .osm.bz2 or .osm.pbf)");
  }
}

}  // namespace

OsmInput::OsmInput(const std::string& path, const ImportLimits& limits, const std::string& source) : file_(path) {
  if (file_.format() == osmium::io::file_format::pbf) {
    pbf_ = read_file(path);
    input_bytes_ = check_pbf(pbf_, limits, source);
    file_ = osmium::io::File(pbf_.data(), pbf_.size(), "pbf");
  } else if (file_.compression() == osmium::io::file_compression::none ||
             (file_.compression() == osmium::io::file_compression::gzip && !starts_like_gzip(path))) {
    // Plain text (zlib's gzread, which libosmium uses, passes a .gz that is not gzip through).
    input_bytes_ = std::filesystem::file_size(path);
    check_limit(input_bytes_, limits.max_osm_decompressed_bytes, "max_osm_decompressed_bytes", source,
                "bytes of OSM data");
    file_ = osmium::io::File(path, plain_format(file_, source));
  } else {
    const auto format = plain_format(file_, source);
    spool_.emplace();
    input_bytes_ = decompress_osm(
        path, file_.compression() == osmium::io::file_compression::gzip ? OsmCompression::gzip : OsmCompression::bzip2,
        *spool_, limits.max_osm_decompressed_bytes, source);
    file_ = osmium::io::File(spool_->path(), format);
  }
}

const char* tag_value(const osmium::TagList& tags, const char* key) {
  const char* p = reinterpret_cast<const char*>(tags.data()) + sizeof(osmium::TagList);
  const char* const end = reinterpret_cast<const char*>(tags.data()) + tags.byte_size();
  while (p < end) {
    const auto* key_end = static_cast<const char*>(std::memchr(p, '\0', static_cast<std::size_t>(end - p)));
    if (!key_end || key_end + 1 >= end) return nullptr;
    const char* value = key_end + 1;
    const auto* value_end = static_cast<const char*>(std::memchr(value, '\0', static_cast<std::size_t>(end - value)));
    if (!value_end) return nullptr;
    if (std::strcmp(p, key) == 0) return value;
    p = value_end + 1;
  }
  return nullptr;
}

bool well_formed_tags(const osmium::TagList& tags) {
  const char* const begin = reinterpret_cast<const char*>(tags.data()) + sizeof(osmium::TagList);
  const char* const end = reinterpret_cast<const char*>(tags.data()) + tags.byte_size();
  if (begin == end) return true;
  if (end < begin || end[-1] != '\0') return false;
  return std::count(begin, end, '\0') % 2 == 0;
}

std::optional<geo::LonLat> way_centre(const osmium::Way& way) {
  double lon = 0, lat = 0;
  std::size_t n = 0;
  const auto& nodes = way.nodes();
  const bool closed = nodes.size() > 2 && nodes.front().ref() == nodes.back().ref();
  for (std::size_t i = 0; i + (closed ? 1 : 0) < nodes.size(); ++i)
    if (nodes[i].location().valid()) {
      lon += nodes[i].location().lon();
      lat += nodes[i].location().lat();
      ++n;
    }
  if (n == 0) return std::nullopt;
  return geo::LonLat{lon / static_cast<double>(n), lat / static_cast<double>(n)};
}

}  // namespace tourmap::load
