#pragma once
// The built web client, served from one directory: MIME types, caching headers (hashed Vite
// assets are immutable; index.html is revalidated), ETags, and no path traversal.

#include "api/http.hpp"

#include <filesystem>
#include <optional>
#include <string>

namespace tourmap::server {

class StaticFiles {
 public:
  explicit StaticFiles(std::string root);
  // nullopt when `path` does not name a file under the root (the caller answers 404).
  std::optional<api::Response> serve(const std::string& path) const;
  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;  // canonical
};

std::string mime_type(const std::string& extension);

}  // namespace tourmap::server
