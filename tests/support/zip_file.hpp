#pragma once
// Zip files for tests (GTFS feeds), written with libzip.

#include "temp_dir.hpp"

#include <map>
#include <string>

namespace tourmap::test {

// Writes `files` (name -> bytes) as the zip `name` in `dir`, each under `prefix` ("" or
// "feed/"); returns its path. Throws std::runtime_error when libzip fails.
std::string write_zip(const TempDir& dir, const std::string& name, const std::map<std::string, std::string>& files,
                      const std::string& prefix = "");

}  // namespace tourmap::test
