#pragma once
// A real tourmap server for the integration tests: a fresh database with a small slice of the
// sample data (two cities, two road networks) and a tiny web root, served on a free port.

#include "http_client.hpp"
#include "server_process.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <sstream>
#include <string>

namespace tourmap::test {

// The binary under test; TOURMAP_TEST_BIN runs the suite against another build (an older one,
// to show that a regression test fails without its fix).
inline const char* kTourmapBin = std::getenv("TOURMAP_TEST_BIN") ? std::getenv("TOURMAP_TEST_BIN") : TOURMAP_BIN;

// The manifest the integration tests import (paths relative to the shared data directory).
inline std::string small_manifest() {
  return R"({"cities":[
    {"id":"vienna","name":"Vienna","metro":{"format":"loom","files":["metro/loom_wien.json"],"attribution":"Wiener Linien"},
     "pois":{"file":"poi/vienna_sights_SEHENSWUERDIGOGD.json","category":"sight","attribution":"Stadt Wien"}},
    {"id":"lisbon","name":"Lisbon","metro":{"format":"line-csv","files":["metro/lisbon_metro_stations_metrodroid.csv"]}}],
   "roads":[
    {"id":"west-oakland","name":"West Oakland","file":"roads/West-Oakland.osm.bz2","attribution":"OSM"},
    {"id":"monaco","name":"Monaco","file":"roads/monaco.osm.gz","attribution":"OSM"}]})";
}

class LiveServer {
 public:
  explicit LiveServer(const std::vector<std::string>& extra_flags = {}) {
    dir.write("web/index.html", "<!doctype html><title>tourmap</title>");
    dir.write("web/assets/app-abc.js", "console.log('tourmap')");
    dir.write("outside.txt", "secret");
    auto manifest = dir.write("manifest.json", small_manifest());
    auto imported = run_command({kTourmapBin, "import", "manifest", manifest, "--data-dir", data_dir(), "--db", db()});
    if (imported.exit_code != 0) throw std::runtime_error("import failed: " + imported.output);
    std::vector<std::string> flags = {"--web-root", dir.file("web"), "--access-log", "off"};
    flags.insert(flags.end(), extra_flags.begin(), extra_flags.end());
    server = std::make_unique<ServerProcess>(kTourmapBin, db(), flags);
  }

  std::string db() const { return dir.file("t.db"); }
  unsigned short port() const { return server->port(); }
  // A request the server does not answer fails the test with what the server's threads are
  // doing (tests/support/server_process.hpp).
  HttpResult get(const std::string& target, const std::map<std::string, std::string>& headers = {}) const {
    try {
      return http_get(port(), target, headers);
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string(e.what()) + "\n" + server->diagnose());
    }
  }
  nlohmann::json get_json(const std::string& target) const {
    auto r = get(target);
    if (r.status != 200) throw std::runtime_error(target + " -> " + std::to_string(r.status) + " " + r.body);
    return nlohmann::json::parse(r.body);
  }

  TempDir dir;
  std::unique_ptr<ServerProcess> server;
};

// One gauge or counter sample from /metrics ("name{labels} value" or "name value"); -1 when
// missing.
inline double metric(const LiveServer& s, const std::string& series) {
  std::string body(1, '\n'), line(1, '\n');  // (not "\n" + s: gcc 12 warns falsely about that)
  body += s.get("/metrics").body;
  line += series;
  line += ' ';
  const auto at = body.find(line);
  return at == std::string::npos ? -1 : std::atof(body.c_str() + at + series.size() + 2);
}

// The error object of a 4xx/5xx JSON body.
inline nlohmann::json error_of(const HttpResult& r) { return nlohmann::json::parse(r.body).at("error"); }

inline std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// `tourmap keys create` on the server's database: the key is the one line that looks like one.
inline std::string create_key(const LiveServer& live, const std::string& name = "tests") {
  auto r = run_command({kTourmapBin, "keys", "create", "--name", name, "--db", live.db()});
  if (r.exit_code != 0) throw std::runtime_error("keys create failed: " + r.output);
  std::smatch m;
  if (!std::regex_search(r.output, m, std::regex("tm_[0-9a-f]{16}_[0-9a-f]{64}")))
    throw std::runtime_error("no key in: " + r.output);
  return m.str();
}

inline std::map<std::string, std::string> bearer(const std::string& key) {
  return {{"Authorization", "Bearer " + key}};
}

}  // namespace tourmap::test
