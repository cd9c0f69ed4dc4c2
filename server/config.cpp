#include "config.hpp"

#ifndef TOURMAP_DEFAULT_DATA_DIR
#define TOURMAP_DEFAULT_DATA_DIR "../shared/data"
#endif
#ifndef TOURMAP_DEFAULT_WEB_ROOT
#define TOURMAP_DEFAULT_WEB_ROOT "web/dist"
#endif

namespace tourmap::server {

Config default_config() {
  Config c;
  c.data_dir = TOURMAP_DEFAULT_DATA_DIR;
  c.web_root = TOURMAP_DEFAULT_WEB_ROOT;
  return c;
}

}  // namespace tourmap::server
