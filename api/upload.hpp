#pragma once
// Uploaded import sources: the loaders read files (libosmium picks its reader from the file
// name), so a request body is written to a private temporary directory, named with the
// extension its format needs, and removed when the import is done.

#include <filesystem>
#include <string>
#include <string_view>

namespace tourmap::api {

class UploadDir {
 public:
  // A fresh 0700 directory "tourmap-upload-<pid>-XXXXXX" under `parent` (default: the system
  // temp dir, $TMPDIR); throws on failure. The pid lets a later server tell whose it was.
  explicit UploadDir(const std::filesystem::path& parent = {});
  ~UploadDir();
  UploadDir(const UploadDir&) = delete;
  UploadDir& operator=(const UploadDir&) = delete;

  // Writes `bytes` to `name` (a plain file name) in the directory; returns its path.
  std::string write(const std::string& name, std::string_view bytes) const;

 private:
  std::filesystem::path dir_;
};

// Removes upload directories under `parent` (default: the system temp dir) left by processes
// that no longer run: a server killed during an upload (kill -9, OOM) cannot remove its own.
// Directories of running processes are left alone, so servers may share a temp dir. Returns
// how many were removed; never throws.
std::size_t remove_stale_uploads(const std::filesystem::path& parent = {});

// File name extensions by content, for bodies sent without a `format`:
//   OSM: "osm.pbf" (OSMHeader blob), "osm.gz" (gzip), "osm.bz2" (bzip2), "osm" (XML); "" unknown.
std::string sniff_osm_extension(std::string_view bytes);
//   POIs: an OSM extract's extension (as above), "json" (GeoJSON object), "js" (JSON array or
//   `var x = [...]`), else "csv".
std::string sniff_poi_extension(std::string_view bytes);

}  // namespace tourmap::api
