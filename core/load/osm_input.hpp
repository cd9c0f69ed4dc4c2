#pragma once
// Bounded input for the OSM road loader (osm_roads.cpp). libosmium decompresses .gz/.bz2 in
// background threads with no bound on the output and no way to stop it early, and decodes
// every PBF blob it finds; these helpers bound both before libosmium sees the data:
//  - decompress_osm() inflates a .gz (every member) or .bz2 (every stream) in 1 MiB chunks into
//    a SpoolFile, stopping with LimitExceeded at ImportLimits::max_osm_decompressed_bytes and
//    polling util::check_stop() after every chunk; libosmium then parses the plain file;
//  - scan_pbf_blobs() walks the framing of a .osm.pbf held in memory and sums its blobs' raw
//    (decompressed) sizes, which libosmium itself only checks blob by blob.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace tourmap::load {

enum class OsmCompression { none, gzip, bzip2 };

// A temporary file for decompressed data, removed from the directory as soon as it is created
// (where /proc/self/fd lets it be reopened by path) so that nothing is left behind even if
// the process is killed; closed (and removed, otherwise) by the destructor.
class SpoolFile {
 public:
  SpoolFile();  // under std::filesystem::temp_directory_path(); throws LoadError when it cannot
  ~SpoolFile();
  SpoolFile(const SpoolFile&) = delete;
  SpoolFile& operator=(const SpoolFile&) = delete;

  int fd() const { return fd_; }
  // A path that opens the file: /proc/self/fd/N, or its name where /proc is not mounted.
  const std::string& path() const { return path_; }
  // Writes all of `data`; throws LoadError (e.g. disk full).
  void write(const char* data, std::size_t size);

 private:
  int fd_ = -1;
  std::string path_;
  std::string name_;  // non-empty while the file still has a name to remove
};

// Decompresses `path` into `out`. gzip: concatenated members are read in turn, bytes after the
// last member that do not start another are ignored (as zlib's gzread does); bzip2: the same
// for concatenated streams. Returns the decompressed size. Throws LimitExceeded
// ("max_osm_decompressed_bytes") as soon as the output passes `max_bytes`, LoadError "cannot
// read OSM data: ..." on corrupt or truncated input, util::Stopped from check_stop().
std::uint64_t decompress_osm(const std::string& path, OsmCompression compression, SpoolFile& out,
                             std::uint64_t max_bytes, const std::string& source);

// True when the file starts with the gzip magic bytes.
bool starts_like_gzip(const std::string& path);

struct PbfBlobs {
  std::size_t count = 0;        // blobs (the OSMHeader included)
  std::uint64_t raw_bytes = 0;  // their decompressed sizes (raw_size, or the raw data's size)
};
// Walks the blobs of a PBF. Stops quietly at malformed framing (libosmium reports it when it
// gets there, having decoded only the blobs before) or once `max_blobs` or `max_raw_bytes` is
// passed (the caller checks the result).
PbfBlobs scan_pbf_blobs(std::string_view pbf, std::size_t max_blobs, std::uint64_t max_raw_bytes);

}  // namespace tourmap::load
