#include "static_files.hpp"

#include <fstream>
#include <map>
#include <sstream>

namespace tourmap::server {

namespace fs = std::filesystem;

std::string mime_type(const std::string& ext) {
  static const std::map<std::string, std::string> types = {
      {".html", "text/html; charset=utf-8"},   {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"}, {".css", "text/css; charset=utf-8"},
      {".json", "application/json"},           {".geojson", "application/geo+json"},
      {".yaml", "application/yaml"},           {".svg", "image/svg+xml"},
      {".png", "image/png"},                   {".jpg", "image/jpeg"},
      {".jpeg", "image/jpeg"},                 {".gif", "image/gif"},
      {".webp", "image/webp"},                 {".ico", "image/x-icon"},
      {".woff2", "font/woff2"},                {".woff", "font/woff"},
      {".txt", "text/plain; charset=utf-8"},   {".map", "application/json"},
      {".wasm", "application/wasm"}};
  auto it = types.find(ext);
  return it == types.end() ? "application/octet-stream" : it->second;
}

StaticFiles::StaticFiles(std::string root) {
  std::error_code ec;
  root_ = fs::weakly_canonical(fs::path(root), ec);
  if (ec) root_ = fs::path(root);
}

std::optional<api::Response> StaticFiles::serve(const std::string& path) const {
  // The decoded path must be a plain relative file path: no '..', no backslashes.
  if (path.empty() || path[0] != '/' || path.find('\\') != std::string::npos) return std::nullopt;
  std::string rel = path == "/" ? "index.html" : path.substr(1);
  for (const auto& part : fs::path(rel))
    if (part == ".." || part == ".") return std::nullopt;

  std::error_code ec;
  auto full = fs::weakly_canonical(root_ / rel, ec);
  if (ec) return std::nullopt;
  // Symlinks out of the root are refused too: the canonical path must stay under the root.
  auto [root_end, full_it] = std::mismatch(root_.begin(), root_.end(), full.begin(), full.end());
  if (root_end != root_.end()) return std::nullopt;
  if (fs::is_directory(full, ec)) full /= "index.html";
  if (!fs::is_regular_file(full, ec)) return std::nullopt;

  std::ifstream in(full, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream buf;
  buf << in.rdbuf();

  api::Response r;
  r.body = std::move(buf).str();
  r.content_type = mime_type(full.extension().string());
  r.cacheable = true;
  // Vite puts content-hashed files under assets/: safe to cache forever.
  bool hashed = rel.rfind("assets/", 0) == 0;
  r.headers.emplace_back("Cache-Control", hashed ? "public, max-age=31536000, immutable" : "no-cache");
  r.headers.emplace_back("X-Content-Type-Options", "nosniff");
  return r;
}

}  // namespace tourmap::server
