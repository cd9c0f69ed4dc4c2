// kill -9 during an import: the database stays intact (integrity check, foreign keys) and the
// import is either whole or absent, never partial. The victim is a real `tourmap import` (and a
// server importing an upload), killed at a spread of moments from parsing through the commit.

#include "live_server.hpp"
#include "slowdown.hpp"

#include "store/migrate.hpp"
#include "store/sqlite.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

namespace tourmap::test {
namespace {

// Starts argv with stdout/stderr to /dev/null, SIGKILLs it after `delay` unless it ended;
// returns true when the kill landed (the process was still running).
bool run_and_kill(const std::vector<std::string>& argv, std::chrono::milliseconds delay) {
  pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  std::this_thread::sleep_for(delay);
  int status = 0;
  const bool running = waitpid(pid, &status, WNOHANG) == 0;
  if (running) kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return running && WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

std::int64_t scalar(store::Db& db, const std::string& sql) {
  auto st = db.prepare(sql);
  st.step();
  return st.int64(0);
}

// What the database holds for road network `id` after a crash: checks integrity and that the
// network is complete when present; returns its node count (0: absent).
std::int64_t check_road_network(const std::string& path, const std::string& id) {
  store::Db db(path);  // opening runs WAL recovery
  {
    auto st = db.prepare("PRAGMA integrity_check");
    EXPECT_TRUE(st.step());
    EXPECT_EQ(st.text(0), "ok");
  }
  EXPECT_EQ(scalar(db, "SELECT COUNT(*) FROM pragma_foreign_key_check"), 0);
  auto st = db.prepare("SELECT node_count, way_count, edge_count, version FROM road_networks WHERE id = ?");
  st.bind(1, id);
  if (!st.step()) {
    // Absent: no rows of it anywhere.
    EXPECT_EQ(scalar(db, "SELECT COUNT(*) FROM road_nodes WHERE network_id = '" + id + "'"), 0);
    EXPECT_EQ(scalar(db, "SELECT COUNT(*) FROM road_edges WHERE network_id = '" + id + "'"), 0);
    return 0;
  }
  const auto nodes = st.int64(0), ways = st.int64(1), edges = st.int64(2), version = st.int64(3);
  st.reset();
  EXPECT_EQ(scalar(db, "SELECT COUNT(*) FROM road_nodes WHERE network_id = '" + id + "'"), nodes);
  EXPECT_EQ(scalar(db, "SELECT COUNT(*) FROM road_ways WHERE network_id = '" + id + "'"), ways);
  EXPECT_EQ(scalar(db, "SELECT COUNT(*) FROM road_edges WHERE network_id = '" + id + "'"), edges);
  // The import log row that stamped it is there too.
  EXPECT_EQ(scalar(db, "SELECT COUNT(*) FROM imports WHERE id = " + std::to_string(version) +
                           " AND kind = 'roads' AND target_id = '" + id + "'"),
            1);
  return nodes;
}

constexpr std::int64_t kMonacoNodes = 4709;
constexpr std::int64_t kLiechtensteinNodes = 54374;

TEST(Durability, KillDuringCliImportLeavesOldOrNewNetwork) {
  TempDir dir;
  const auto db = dir.file("t.db");
  // A network to replace: Monaco under the id "net".
  auto r = run_command({kTourmapBin, "import", "roads", data_file("roads/monaco.osm.gz"), "--id", "net", "--name", "Net",
                        "--db", db});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_EQ(check_road_network(db, "net"), kMonacoNodes);

  // How long replacing it with Liechtenstein (~115K rows) takes here, from exec to exit, so the
  // kills spread across the import whatever the machine's speed; then Monaco back.
  const auto liechtenstein = std::vector<std::string>{kTourmapBin, "import", "roads",
                                                      data_file("roads/liechtenstein-latest.osm.pbf"), "--id", "net",
                                                      "--name", "Net", "--force", "--db", db};
  const auto monaco = std::vector<std::string>{kTourmapBin, "import", "roads", data_file("roads/monaco.osm.gz"), "--id",
                                               "net", "--name", "Net", "--force", "--db", db};
  const auto t0 = std::chrono::steady_clock::now();
  r = run_command(liechtenstein);
  const auto whole_ms = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_EQ(check_road_network(db, "net"), kLiechtensteinNodes);
  r = run_command(monaco);
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // Kills at 13 moments from 3 % to 95 % of that time: parsing, writing rows, the commit. Under
  // the sanitizers, whose run looks for memory errors rather than torn imports, at 7 of them
  // (each round imports for seconds there: 13 rounds took 70-90 s of the CI's time).
  const int kRounds = kSlowdown > 1 ? 7 : 13;
  int killed = 0, old_kept = 0, new_whole = 0;
  for (int i = 0; i < kRounds; ++i) {
    const auto ms = std::max<std::int64_t>(1, whole_ms * (3 + i * 92 / (kRounds - 1)) / 100);
    bool landed = run_and_kill(liechtenstein, std::chrono::milliseconds(ms));
    killed += landed;
    auto nodes = check_road_network(db, "net");
    EXPECT_TRUE(nodes == kMonacoNodes || nodes == kLiechtensteinNodes) << "after a kill at " << ms << " ms: " << nodes;
    old_kept += nodes == kMonacoNodes;
    new_whole += nodes == kLiechtensteinNodes;
    if (nodes == kLiechtensteinNodes) {  // committed: put Monaco back for the next round
      r = run_command(monaco);
      ASSERT_EQ(r.exit_code, 0) << r.output;
    }
  }
  std::printf("[durability] a whole import took %lld ms; %d of %d kills landed; old network kept %d times, new one "
              "whole %d times\n",
              static_cast<long long>(whole_ms), killed, kRounds, old_kept, new_whole);
  EXPECT_GE(killed, kRounds / 2);  // most kills hit a running import (timing varies with the load)
  EXPECT_GT(old_kept, 0);          // some before the commit

  // The database keeps working: a normal import completes and is served.
  r = run_command(liechtenstein);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(check_road_network(db, "net"), kLiechtensteinNodes);
}

TEST(Durability, KillServerDuringUploadImport) {
  TempDir dir;
  const auto db = dir.file("t.db");
  auto r = run_command({kTourmapBin, "keys", "create", "--name", "t", "--db", db});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto key = r.output.substr(r.output.find("tm_"), 3 + 16 + 1 + 64);
  std::ifstream in(data_file("roads/liechtenstein-latest.osm.pbf"), std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();

  for (int ms : {150, 300, 450}) {
    ServerProcess server(kTourmapBin, db, {"--access-log", "off"});
    std::thread upload([&] {
      try {
        http_request(server.port(), "PUT", "/api/v1/roads/net?name=Net&force=true", {{"X-API-Key", key}},
                     bytes.str());
      } catch (const std::exception&) {  // the server died under the request: expected
      }
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(ms));
    kill(server.pid(), SIGKILL);
    upload.join();
    server.stop(5);
    auto nodes = check_road_network(db, "net");
    EXPECT_TRUE(nodes == 0 || nodes == kLiechtensteinNodes) << "after a kill at " << ms << " ms: " << nodes;
  }
  // A restarted server serves from the same file.
  ServerProcess server(kTourmapBin, db, {"--access-log", "off"});
  EXPECT_EQ(http_get(server.port(), "/healthz").status, 200);
}

}  // namespace
}  // namespace tourmap::test
