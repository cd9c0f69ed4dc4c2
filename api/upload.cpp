#include "upload.hpp"

#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace tourmap::api {

namespace fs = std::filesystem;

UploadDir::UploadDir() {
  std::string pattern = (fs::temp_directory_path() / "tourmap-upload-XXXXXX").string();
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  if (!::mkdtemp(buf.data())) throw std::runtime_error("cannot create a temporary directory for the upload");
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
  if (!out) throw std::runtime_error("cannot write the upload to " + path);
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
  auto text = skip_space(bytes);
  if (!text.empty() && text.front() == '{') return "json";
  if (!text.empty() && text.front() == '[') return "js";
  for (std::string_view kw : {"var ", "let ", "const "})
    if (text.substr(0, kw.size()) == kw) return "js";
  return "csv";
}

}  // namespace tourmap::api
