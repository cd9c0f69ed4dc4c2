#include "load/file.hpp"

#include "load/load_error.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace tourmap::load {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw LoadError(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream buf;
  buf << in.rdbuf();
  if (in.bad()) throw LoadError(path, "read failed");
  return std::move(buf).str();
}

std::string file_name(const std::string& path) {
  auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace tourmap::load
