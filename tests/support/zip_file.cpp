#include "zip_file.hpp"

#include <zip.h>

#include <stdexcept>

namespace tourmap::test {

std::string write_zip(const TempDir& dir, const std::string& name, const std::map<std::string, std::string>& files,
                      const std::string& prefix) {
  const auto path = dir.file(name);
  int error = 0;
  zip_t* zip = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (!zip) throw std::runtime_error("zip_open failed");
  for (const auto& [file, text] : files) {  // the texts outlive zip_close
    zip_source_t* source = zip_source_buffer(zip, text.data(), text.size(), 0);
    if (!source || zip_file_add(zip, (prefix + file).c_str(), source, ZIP_FL_OVERWRITE) < 0) {
      zip_discard(zip);
      throw std::runtime_error("zip_file_add failed");
    }
  }
  if (zip_close(zip) != 0) throw std::runtime_error("zip_close failed");
  return path;
}

}  // namespace tourmap::test
