#pragma once
// Bounded input for the OSM loaders (osm_roads.cpp, osm_context.cpp). libosmium decompresses
// .gz/.bz2 in background threads with no bound on the output and no way to stop it early, and
// decodes every PBF blob it finds; these helpers bound both before libosmium sees the data:
//  - decompress_osm() inflates a .gz (every member) or .bz2 (every stream) in 1 MiB chunks into
//    a SpoolFile, stopping with LimitExceeded at ImportLimits::max_osm_decompressed_bytes and
//    polling util::check_stop() after every chunk; libosmium then parses the plain file;
//  - scan_pbf_blobs() walks the framing of a .osm.pbf held in memory and sums its blobs' raw
//    (decompressed) sizes, which libosmium itself only checks blob by blob;
//  - OsmInput puts both together for a loader (osm_roads.cpp, osm_context.cpp): the extract,
//    bounded, as an osmium::io::File that can be read more than once.
// And tag_value()/well_formed_tags(): reading tags safely (see there).

#include "geo/lonlat.hpp"
#include "load/import_limits.hpp"

#include <osmium/io/file.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace osmium {
class TagList;
class Way;
}

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

// An OSM extract (.osm, .osm.gz, .osm.bz2, .osm.pbf; also .opl and .o5m) ready for libosmium,
// its input bounded by `limits` before libosmium reads it:
//  - a PBF is read into memory (libosmium reads a .pbf through a descriptor of its own that it
//    closes only after a successful read: every PBF that failed to parse leaked one) and its
//    blobs are counted and their sizes summed (max_osm_pbf_blobs, max_osm_decompressed_bytes);
//  - compressed XML is decompressed here, bounded and stoppable, into a SpoolFile that
//    libosmium then reads as plain text (its own decompression has no bound);
//  - plain text is read as it is, its size checked.
// file() may be opened by any number of osmium::io::Readers in turn (a loader reading twice
// decompresses once). Throws LoadError (unsupported format, unreadable or corrupt compressed
// data), LimitExceeded, util::Stopped; leaves nothing behind when it throws or is destroyed.
class OsmInput {
 public:
  OsmInput(const std::string& path, const ImportLimits& limits, const std::string& source);
  OsmInput(const OsmInput&) = delete;
  OsmInput& operator=(const OsmInput&) = delete;

  const osmium::io::File& file() const { return file_; }
  // OSM data to parse: decompressed XML, or the PBF blobs' raw sizes.
  std::uint64_t input_bytes() const { return input_bytes_; }

 private:
  std::string pbf_;                 // the PBF, when the file is one (file_ points into it)
  std::optional<SpoolFile> spool_;  // the decompressed XML, when the file was compressed
  osmium::io::File file_;
  std::uint64_t input_bytes_ = 0;
};

// The value of tag `key`, or nullptr, reading the tag list's bytes (key NUL value NUL ...)
// strictly within the list. TagList::operator[] walks the list with strchr and trusts its
// shape, but libosmium's PBF reader copies string-table entries with NUL bytes inside them as
// they are: the walk then gets out of step and runs past the end of the list (a heap overread
// on a crafted .osm.pbf). Here such a list simply ends at its last complete pair.
const char* tag_value(const osmium::TagList& tags, const char* key);

// The mean of a way's distinct node locations (a closed way's first node once), or none when
// no node is located (all outside the extract): where a POI or a platform mapped as a way is.
std::optional<geo::LonLat> way_centre(const osmium::Way& way);

// True when the tag list is whole pairs of NUL-terminated strings, exactly filling the list:
// only then may it go to libosmium code that walks it (the area assembler, the relations
// manager's filters, TagList iterators), which would otherwise read past its end (above).
bool well_formed_tags(const osmium::TagList& tags);

}  // namespace tourmap::load
