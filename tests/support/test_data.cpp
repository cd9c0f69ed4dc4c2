#include "test_data.hpp"

#include <cstdlib>

namespace tourmap::test {

std::string data_dir() {
  if (const char* env = std::getenv("TOURMAP_DATA_DIR"); env && *env) return env;
  return TOURMAP_TEST_DATA_DIR;
}

std::string data_file(const std::string& relative) { return data_dir() + "/" + relative; }

}  // namespace tourmap::test
