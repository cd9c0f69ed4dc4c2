#include "config.hpp"

#ifndef TOURMAP_DEFAULT_DATA_DIR
#define TOURMAP_DEFAULT_DATA_DIR "../shared/data"
#endif
#ifndef TOURMAP_DEFAULT_WEB_ROOT
#define TOURMAP_DEFAULT_WEB_ROOT "web/dist"
#endif

#include <charconv>
#include <stdexcept>

namespace tourmap::server {

load::ImportLimits import_limits_of(const Config& config) {
  load::ImportLimits limits;
  for (const auto& entry : config.import_limits) {
    const auto eq = entry.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("'" + entry + "' is not NAME=VALUE");
    const std::string name = entry.substr(0, eq);
    std::uint64_t value = 0;
    const char* first = entry.data() + eq + 1;
    const char* last = entry.data() + entry.size();
    const auto [end, ec] = std::from_chars(first, last, value);
    if (first == last || ec != std::errc() || end != last)
      throw std::invalid_argument("'" + entry + "': the value must be a whole number");
    if (!load::set_limit(limits, name, value))
      throw std::invalid_argument("no import limit called '" + name + "' (tourmap serve --help-limits lists them)");
  }
  return limits;
}

Config default_config() {
  Config c;
  c.data_dir = TOURMAP_DEFAULT_DATA_DIR;
  c.web_root = TOURMAP_DEFAULT_WEB_ROOT;
  return c;
}

}  // namespace tourmap::server
