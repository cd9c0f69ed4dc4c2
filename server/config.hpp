#pragma once
// Server configuration: defaults, overridden by TOURMAP_* environment variables, overridden by
// command-line flags (`tourmap serve --help` lists them).

#include "load/import_limits.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace tourmap::server {

struct Config {
  std::string host = "127.0.0.1";
  unsigned short port = 8080;      // 0 picks a free port (printed at start)
  std::string db_path = "var/tourmap.db";
  std::string data_dir;            // sample data (../shared/data by default)
  std::string web_root;            // built web client
  unsigned io_threads = 2;
  // Expensive requests (layouts, deformations, rasters, clusters, imports): the compute pool.
  unsigned compute_threads = 0;    // 0: two per core (many of its tasks wait on a MIP child process)
  std::size_t compute_queue = 256;         // queued compute requests before 503
  double compute_deadline_s = 30.0;        // a request still queued after this gets 503 (at once)
  double compute_timeout_s = 120.0;        // a running computation is stopped after this (503)
  std::size_t max_compute_per_client = 2;  // queued or running per client address (429 beyond; 0: no cap)
  // Cheap reads (catalog, metro, POIs, roads): their own pool, never behind the compute pool.
  unsigned read_threads = 2;
  std::size_t read_queue = 512;
  double read_deadline_s = 10.0;
  std::size_t max_reads_per_client = 64;   // queued or running per client address (429 beyond; 0: no cap)
  std::size_t max_body_bytes = 1 << 20;    // 413 beyond
  std::size_t max_upload_bytes = 64 << 20; // bodies of write requests with a valid API key (imports)
  std::size_t max_header_bytes = 16 << 10; // 431 beyond; also the budget of chunked trailers
  std::size_t max_header_fields = 100;     // header plus trailer fields (431 beyond)
  double request_timeout_s = 30.0;         // to read a request once it started
  double idle_timeout_s = 60.0;            // keep-alive connection without a request
  double drain_timeout_s = 10.0;           // graceful shutdown: time for in-flight requests
  std::size_t gzip_min_bytes = 1024;       // smaller bodies are sent as they are
  std::string access_log = "-";            // "-" stdout, "off", or a file path
  std::size_t max_ws_connections = 256;
  unsigned max_crowd_streams = 4;         // WS /api/v1/crowd/stream refuses more (close 1013)
  int crowd_max_subdivision = -1;         // caps the scenes' Loop levels (-1: as the scene says)
  double improve_mip_s = 10.0;            // CBC CPU seconds of a background layout improvement (0: none)
  double rate_limit = 200.0;              // requests per second per client address (0: no limit)
  double rate_burst = 400.0;              // requests a client may make at once (token bucket size)
  std::string cors_origins;               // comma-separated allowed origins, "*" any; empty: no CORS
  std::string trusted_proxies;            // comma-separated addresses/CIDRs whose X-Forwarded-For is believed
  // Import limits of uploads, NAME=VALUE (load/import_limits.hpp names them); the rest keep
  // their defaults.
  std::vector<std::string> import_limits;
};

// Built-in defaults for paths (from the build: the source's ../shared/data and build/web).
Config default_config();

// The import limits of uploads: the defaults, with `import_limits` ("NAME=VALUE") applied.
// Throws std::invalid_argument naming a bad entry (unknown name, not a number).
load::ImportLimits import_limits_of(const Config& config);

// The largest --max-header: Beast's field table holds names and values below 64 KiB.
inline constexpr std::size_t kMaxHeaderBytesLimit = 60u << 10;

}  // namespace tourmap::server
