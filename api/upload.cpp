#include "upload.hpp"

#include "http.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace tourmap::api {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kPrefix = "tourmap-upload-";

fs::path parent_or_temp(const fs::path& parent) { return parent.empty() ? fs::temp_directory_path() : parent; }

// The pid in "tourmap-upload-<pid>-XXXXXX", or 0.
pid_t owner_pid(const std::string& name) {
  if (name.rfind(kPrefix, 0) != 0) return 0;
  const char* p = name.c_str() + kPrefix.size();
  char* end = nullptr;
  const long pid = std::strtol(p, &end, 10);
  if (end == p || *end != '-' || pid <= 0) return 0;
  return static_cast<pid_t>(pid);
}

}  // namespace

std::size_t remove_stale_uploads(const fs::path& parent) {
  std::size_t removed = 0;
  std::error_code ec;
  const fs::path dir = parent.empty() ? fs::temp_directory_path(ec) : parent;
  if (ec) return 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const pid_t pid = owner_pid(it->path().filename().string());
    if (pid == 0 || !it->is_directory(ec)) continue;
    if (::kill(pid, 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to ask about)
    std::error_code rm_ec;
    if (fs::remove_all(it->path(), rm_ec) != static_cast<std::uintmax_t>(-1) && !rm_ec) ++removed;
  }
  return removed;
}

UploadDir::UploadDir(const fs::path& parent) {
  std::string pattern =
      (parent_or_temp(parent) / (std::string(kPrefix) + std::to_string(::getpid()) + "-XXXXXX")).string();
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  if (!::mkdtemp(buf.data()))
    throw ApiError(507, "insufficient_storage", "the server cannot store the upload now (no temporary directory)",
                   "body");
  dir_ = buf.data();
}

UploadDir::~UploadDir() {
  std::error_code ec;
  fs::remove_all(dir_, ec);
}

std::string UploadDir::write(const std::string& name, std::string_view bytes) const {
  auto path = (dir_ / name).string();
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  // Out of disk (or quota): the server's condition, not the client's; nothing was imported.
  if (!out)
    throw ApiError(507, "insufficient_storage", "the server cannot store the upload now (disk full?); nothing was imported",
                   "body");
  return path;
}

namespace {

std::string_view skip_space(std::string_view s) {
  if (s.size() >= 3 && s.substr(0, 3) == "\xEF\xBB\xBF") s.remove_prefix(3);  // UTF-8 BOM
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r' || s.front() == '\n'))
    s.remove_prefix(1);
  return s;
}

}  // namespace

std::string sniff_osm_extension(std::string_view bytes) {
  if (bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f && static_cast<unsigned char>(bytes[1]) == 0x8b)
    return "osm.gz";
  if (bytes.substr(0, 3) == "BZh") return "osm.bz2";
  // PBF: a 4-byte big-endian header length, then a BlobHeader whose type string is "OSMHeader".
  if (bytes.size() > 16 && bytes.substr(4, 32).find("OSMHeader") != std::string_view::npos) return "osm.pbf";
  auto text = skip_space(bytes);
  if (text.substr(0, 5) == "<?xml" || text.substr(0, 4) == "<osm") return "osm";
  return "";
}

std::string sniff_poi_extension(std::string_view bytes) {
  if (auto osm = sniff_osm_extension(bytes); !osm.empty()) return osm;  // an extract's tourist places
  auto text = skip_space(bytes);
  if (!text.empty() && text.front() == '{') return "json";
  if (!text.empty() && text.front() == '[') return "js";
  for (std::string_view kw : {"var ", "let ", "const "})
    if (text.substr(0, kw.size()) == kw) return "js";
  return "csv";
}

}  // namespace tourmap::api
