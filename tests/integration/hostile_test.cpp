// A hostile client against a real server (issue 12): each finding of the review, reproduced as
// it was found (raw sockets for what HTTP clients would not send), must now get a 4xx, 429 or
// 503 within its limit while GET /api/v1/cities keeps answering fast, and the server must keep
// serving. Latency bounds are loose under the sanitizers (everything runs 5-20x slower there).

#include "live_server.hpp"
#include "slowdown.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <mutex>
#include <regex>
#include <sstream>
#include <thread>

namespace tourmap::test {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

constexpr double kSlow = kSlowdown;  // slowdown.hpp

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// --- raw sockets ---

int connect_to(unsigned short port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (fd < 0 || ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    if (fd >= 0) ::close(fd);
    return -1;
  }
  return fd;
}

// Sends `bytes` (on a thread: the server may answer and stop reading long before the end)
// and returns everything it answers until it closes, or until `timeout`.
std::string exchange(unsigned short port, const std::string& bytes, std::chrono::milliseconds timeout = 10s) {
  const int fd = connect_to(port);
  if (fd < 0) return "";
  std::thread sender([fd, &bytes] {
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::send(fd, bytes.data() + done, std::min<std::size_t>(bytes.size() - done, 1 << 16), MSG_NOSIGNAL);
      if (n <= 0) break;
      done += static_cast<std::size_t>(n);
    }
  });
  std::string out;
  const auto deadline = Clock::now() + timeout;
  char buf[16384];
  while (Clock::now() < deadline) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 50) <= 0) continue;
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    out.append(buf, static_cast<std::size_t>(n));
  }
  ::shutdown(fd, SHUT_RDWR);  // unblocks the sender
  sender.join();
  ::close(fd);
  return out;
}

int status_of(const std::string& response) {
  if (response.rfind("HTTP/1.1 ", 0) != 0 || response.size() < 12) return 0;
  return std::atoi(response.substr(9, 3).c_str());
}

long rss_kb(int pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
  return -1;
}

// utime + stime of a process, in seconds.
double cpu_seconds(int pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(in)), {});
  std::istringstream fields(stat.substr(stat.rfind(')') + 2));
  std::string f;
  unsigned long utime = 0, stime = 0;
  for (int i = 3; i <= 15 && fields >> f; ++i) {
    if (i == 14) utime = std::stoul(f);
    if (i == 15) stime = std::stoul(f);
  }
  return static_cast<double>(utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

// Samples GET /api/v1/cities every 50 ms on its own connection while an attack runs.
class CheapReadProbe {
 public:
  explicit CheapReadProbe(unsigned short port)
      : thread_([this, port] {
          do {  // at least one sample, however short the attack
            const auto t0 = Clock::now();
            int status = 0;
            try {
              status = http_get(port, "/api/v1/cities").status;
            } catch (const std::exception&) {  // no answer at all: the server died or hung up
            }
            const double ms = ms_since(t0);
            {
              std::lock_guard lock(mutex_);
              samples_.push_back(ms);
              if (status != 200) ++failures_;
            }
            std::this_thread::sleep_for(50ms);
          } while (!stop_);
        }) {}
  ~CheapReadProbe() { finish(); }
  void finish() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  // Checks the samples: all answered 200, the median within 50 ms, none slower than 1 s.
  void expect_fast(const std::string& during) {
    finish();
    std::lock_guard lock(mutex_);
    ASSERT_GE(samples_.size(), 1u) << during;
    auto sorted = samples_;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[sorted.size() / 2], worst = sorted.back();
    EXPECT_EQ(failures_, 0) << during;
    EXPECT_LT(median, 50.0 * kSlow) << during << ": GET /api/v1/cities median " << median << " ms over "
                                    << sorted.size() << " samples";
    EXPECT_LT(worst, 1000.0 * kSlow) << during << ": GET /api/v1/cities worst " << worst << " ms";
    std::printf("[probe] %s: GET /api/v1/cities n=%zu median %.1f ms, worst %.1f ms\n", during.c_str(), sorted.size(),
                median, worst);
  }

 private:
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::vector<double> samples_;
  int failures_ = 0;
  std::thread thread_;
};

// A computation that runs to its time limit: Berlin's MIP (about 700 columns) is not solved
// within 20 s, where Vienna's (about 330 columns since the layouts have fewer segments) is
// solved to optimality in 1-4 s, too soon for the deadline tests below. Berlin is not in the
// test manifest (other tests count its cities): the tests that need it import it first.
void import_berlin(const LiveServer& live) {
  const auto r = run_command({kTourmapBin, "import", "metro", data_file("metro/loom_berlin.json"), "--city", "berlin",
                              "--name", "Berlin", "--db", live.db()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
}

std::string layout_mip(double time_limit_s, double w_r) {
  char target[160];
  std::snprintf(target, sizeof target, "/api/v1/cities/berlin/layout?solver=mip&time_limit_s=%g&w_r=%g", time_limit_s,
                w_r);
  return target;
}

// --- C1, C2: chunked trailers ---

TEST(Hostile, OversizedTrailerFieldIsRefusedNotFatal) {
  LiveServer live({"--max-header", "61440"});  // the largest header limit: the field still exceeds it
  CheapReadProbe probe(live.port());
  const std::string request = "GET /healthz HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n0\r\nX: " +
                              std::string(70000, 'a') + "\r\n\r\n";
  const auto response = exchange(live.port(), request);
  EXPECT_EQ(status_of(response), 431) << response.substr(0, 200);
  EXPECT_NE(response.find("header_too_large"), std::string::npos);
  EXPECT_EQ(live.get("/healthz").status, 200) << "the server died";
  probe.expect_fast("C1 oversized trailer field");
  EXPECT_EQ(metric(live, "tourmap_io_handler_exceptions"), 0.0);
}

TEST(Hostile, TrailerFloodIsBoundedInTimeAndMemory) {
  LiveServer live;
  const long rss_before = rss_kb(live.server->pid());
  CheapReadProbe probe(live.port());
  std::string request = "GET /healthz HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n";
  request.reserve(request.size() + 5'000'000 * 6 + 2);
  for (int i = 0; i < 5'000'000; ++i) request += "X: 1\r\n";
  request += "\r\n";
  const auto t0 = Clock::now();
  const auto response = exchange(live.port(), request);
  EXPECT_EQ(status_of(response), 431) << response.substr(0, 200);
  EXPECT_LT(ms_since(t0), 3000 * kSlow);
  // Many small trailer fields count against the field limit too.
  std::string few = "GET /healthz HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n";
  for (int i = 0; i < 150; ++i) few.append("X").append(std::to_string(i)).append(": 1\r\n");
  EXPECT_EQ(status_of(exchange(live.port(), few + "\r\n")), 431);
  probe.expect_fast("C2 trailer flood");
  const long grown_mb = (rss_kb(live.server->pid()) - rss_before) / 1024;
  EXPECT_LT(grown_mb, 50) << "the server grew by " << grown_mb << " MB";
  // A well-formed chunked request with a small trailer is still served.
  const auto ok = exchange(live.port(),
                           "GET /healthz HTTP/1.1\r\nHost: x\r\nConnection: close\r\nTransfer-Encoding: chunked\r\n\r\n"
                           "0\r\nX-Checksum: 1\r\n\r\n");
  EXPECT_EQ(status_of(ok), 200) << ok;
}

// A refused upload's answer reaches the client although it is still sending (lingering close).
TEST(Hostile, RefusalsReachClientsThatAreStillSending) {
  LiveServer live({"--max-body", "65536"});
  const std::string body(4 << 20, 'x');
  const auto response = exchange(live.port(), "POST /api/v1/deform/focus HTTP/1.1\r\nHost: x\r\nContent-Type: "
                                              "application/json\r\nTransfer-Encoding: chunked\r\n\r\n400000\r\n" +
                                                  body + "\r\n0\r\n\r\n");
  EXPECT_EQ(status_of(response), 413) << response.substr(0, 200);
}

// --- H1: expensive requests, compute isolation and fairness ---

TEST(Hostile, ExpensiveRequestsDoNotStallCheapReads) {
  LiveServer live;  // defaults: 2 compute requests per client address
  import_berlin(live);
  CheapReadProbe probe(live.port());
  std::vector<std::future<HttpResult>> mips;
  for (double w_r : {0.11, 0.22, 0.33, 0.44})
    mips.push_back(std::async(std::launch::async, [&, w_r] { return live.get(layout_mip(3, w_r)); }));
  int ok = 0, refused = 0;
  for (auto& f : mips) {
    const auto r = f.get();
    if (r.status == 200) ++ok;
    if (r.status == 429) {
      ++refused;
      EXPECT_EQ(error_of(r)["code"], "too_many_computations");
      EXPECT_FALSE(r.header("retry-after").empty());
    }
  }
  EXPECT_EQ(ok, 2);
  EXPECT_EQ(refused, 2);
  probe.expect_fast("H1 four MIP layouts from one address");
}

// A queued request is answered 503 when its queue deadline passes, while every worker is still
// busy (it used to wait until a worker freed up: 61 s for a 30 s deadline).
TEST(Hostile, QueueDeadlineHoldsWhileQueued) {
  LiveServer live({"--compute-threads", "1", "--compute-deadline", "1", "--max-compute-per-client", "0"});
  import_berlin(live);
  auto first = std::async(std::launch::async, [&] { return live.get(layout_mip(6, 0.15)); });
  std::this_thread::sleep_for(300ms);  // the first one runs
  const auto t0 = Clock::now();
  const auto queued = live.get(layout_mip(6, 0.25));
  const double waited = ms_since(t0);
  EXPECT_EQ(queued.status, 503) << queued.body;
  EXPECT_EQ(error_of(queued)["code"], "overloaded");
  EXPECT_GE(waited, 900.0);
  EXPECT_LT(waited, 3000.0 * kSlow) << "the queued request waited for the worker, not its deadline";
  EXPECT_EQ(first.get().status, 200);
  EXPECT_GE(metric(live, "tourmap_compute_expired_in_queue"), 1.0);
}

TEST(Hostile, ComputationsStopAtTheirTimeout) {
  LiveServer live({"--compute-timeout", "2"});
  import_berlin(live);
  const auto t0 = Clock::now();
  const auto r = live.get(layout_mip(30, 0.35));
  EXPECT_EQ(r.status, 503) << r.body;
  EXPECT_EQ(error_of(r)["code"], "timeout");
  EXPECT_LT(ms_since(t0), 6000.0 * kSlow);
  const auto t1 = Clock::now();  // the worker frees itself right after handing over the answer
  while (metric(live, "tourmap_compute_busy") != 0.0 && ms_since(t1) < 2000) std::this_thread::sleep_for(20ms);
  EXPECT_EQ(metric(live, "tourmap_compute_busy"), 0.0);
}

TEST(Hostile, ComputationsStopWhenTheirClientLeaves) {
  LiveServer live;
  import_berlin(live);
  const int fd = connect_to(live.port());
  ASSERT_GE(fd, 0);
  const std::string request = "GET " + layout_mip(30, 0.45) + " HTTP/1.1\r\nHost: x\r\n\r\n";
  ASSERT_EQ(::send(fd, request.data(), request.size(), MSG_NOSIGNAL), static_cast<ssize_t>(request.size()));
  std::this_thread::sleep_for(1s);
  EXPECT_EQ(metric(live, "tourmap_compute_busy"), 1.0) << "the MIP layout is not running";
  ::close(fd);  // the client gives up
  const auto t0 = Clock::now();
  while (metric(live, "tourmap_compute_busy") != 0.0 && ms_since(t0) < 5000 * kSlow) std::this_thread::sleep_for(50ms);
  EXPECT_EQ(metric(live, "tourmap_compute_busy"), 0.0) << "the computation went on without its client";
  EXPECT_LT(ms_since(t0), 2000.0 * kSlow);
  EXPECT_NE(live.get("/metrics").body.find("status=\"499\""), std::string::npos);
}

// --- H2: what an import may create (imports with a valid API key) ---

HttpResult put(const LiveServer& live, const std::string& key, const std::string& target, const std::string& body) {
  return http_request(live.port(), "PUT", target, bearer(key), body);
}

void expect_import_limit(const HttpResult& r, const std::string& limit) {
  EXPECT_EQ(r.status, 413) << r.body.substr(0, 300);
  if (r.status != 413) return;
  EXPECT_EQ(error_of(r)["code"], "import_limit");
  EXPECT_EQ(error_of(r)["field"], "body");
  EXPECT_NE(error_of(r)["message"].get<std::string>().find("limit " + limit + " = "), std::string::npos)
      << error_of(r)["message"];
}

TEST(Hostile, PoiImportsAreCappedPerCity) {
  LiveServer live;
  const auto key = create_key(live);
  const auto pois_before = live.get_json("/api/v1/cities/vienna")["counts"]["pois"];
  CheapReadProbe probe(live.port());
  std::string csv = "name,lon,lat\n";
  for (int i = 0; i < 1'000'000; ++i) csv.append("p").append(std::to_string(i)).append(",16.37,48.2\n");
  const auto t0 = Clock::now();
  expect_import_limit(put(live, key, "/api/v1/cities/vienna/pois", csv), "max_pois");
  EXPECT_LT(ms_since(t0), 5000 * kSlow);
  // A name of 60 MB is refused, not stored and served: the CSV field cap stops it while it is
  // read; a name within that cap but beyond a name's length is refused too.
  const std::string huge_name = "name,lon,lat\n" + std::string(60 << 20, 'n') + ",16.37,48.2\n";
  expect_import_limit(put(live, key, "/api/v1/cities/vienna/pois", huge_name), "max_csv_field_bytes");
  const std::string long_name = "name,lon,lat\n" + std::string(2000, 'n') + ",16.37,48.2\n";
  expect_import_limit(put(live, key, "/api/v1/cities/vienna/pois", long_name), "max_name_bytes");
  probe.expect_fast("H2 POI imports");
  // Nothing changed: the reads that grow with the POIs answer as before.
  EXPECT_EQ(live.get_json("/api/v1/cities/vienna")["counts"]["pois"], pois_before);
  EXPECT_EQ(live.get("/api/v1/cities/vienna/visual-worth?width=512&height=512").status, 200);
}

TEST(Hostile, CsvOfCommasFailsFastInLittleMemory) {
  LiveServer live;
  const auto key = create_key(live);
  const long rss_before = rss_kb(live.server->pid());
  const auto t0 = Clock::now();
  expect_import_limit(put(live, key, "/api/v1/cities/lisbon/metro?format=line-csv", std::string(60 << 20, ',')),
                      "max_csv_fields");
  EXPECT_LT(ms_since(t0), 5000 * kSlow);
  // The body (60 MB) was held; parsing it must not have added gigabytes.
  const long grown_mb = (rss_kb(live.server->pid()) - rss_before) / 1024;
  EXPECT_LT(grown_mb, 400 * (kSlow > 1 ? 2 : 1)) << "the server grew by " << grown_mb << " MB";  // ASan's quarantine
}

TEST(Hostile, DuplicateMetroEdgesAreMergedAndLayoutStaysFast) {
  LiveServer live;
  const auto key = create_key(live);
  std::string loom = R"({"type":"FeatureCollection","features":[
    {"type":"Feature","geometry":{"type":"Point","coordinates":[16.36,48.20]},"properties":{"id":"a","station_id":"a","station_label":"A"}},
    {"type":"Feature","geometry":{"type":"Point","coordinates":[16.38,48.21]},"properties":{"id":"b","station_id":"b","station_label":"B"}})";
  for (int i = 0; i < 20'000; ++i)
    loom += R"(,{"type":"Feature","geometry":{"type":"LineString","coordinates":[[16.36,48.20],[16.38,48.21]]},"properties":{"from":"a","to":"b","lines":[{"id":"u1","label":"U1","color":"ff0000"}]}})";
  loom += "]}";
  const auto r = put(live, key, "/api/v1/cities/dupes/metro?name=Dupes&format=loom", loom);
  ASSERT_EQ(r.status, 200) << r.body.substr(0, 300);
  EXPECT_EQ(live.get_json("/api/v1/cities/dupes")["counts"]["edges"], 1);
  CheapReadProbe probe(live.port());
  const auto t0 = Clock::now();
  EXPECT_EQ(live.get("/api/v1/cities/dupes/layout?solver=fast").status, 200);
  EXPECT_LT(ms_since(t0), 2000 * kSlow);
  probe.expect_fast("H2 layout of a deduplicated network");
}

TEST(Hostile, CompressionBombsAreRefusedQuickly) {
  // 256 MiB of decompressed OSM data (default 1 GiB): inflated bytes are spooled to the temp
  // dir, and the test should not need a gigabyte of free disk. The flag is tested on the way.
  LiveServer live({"--import-limit", "max_osm_decompressed_bytes=268435456"});
  const auto key = create_key(live);
  // 2 GiB of spaces after an OSM header, gzip-compressed (~2 MB).
  z_stream z{};
  ASSERT_EQ(deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY), Z_OK);
  std::string bomb(4 << 20, '\0');
  const std::string head = "<?xml version='1.0'?><osm version='0.6'>";
  const std::string spaces(1 << 20, ' ');
  std::size_t out = 0;
  auto pump = [&](const std::string& in, int flush) {
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
    z.avail_in = static_cast<uInt>(in.size());
    do {
      if (out == bomb.size()) bomb.resize(bomb.size() * 2);
      z.next_out = reinterpret_cast<Bytef*>(bomb.data() + out);
      z.avail_out = static_cast<uInt>(bomb.size() - out);
      deflate(&z, flush);
      out = bomb.size() - z.avail_out;
    } while (z.avail_out == 0);
  };
  pump(head, Z_NO_FLUSH);
  for (int i = 0; i < 2048; ++i) pump(spaces, Z_NO_FLUSH);
  pump("</osm>", Z_FINISH);
  deflateEnd(&z);
  bomb.resize(out);
  CheapReadProbe probe(live.port());
  const auto t0 = Clock::now();
  const auto refused = put(live, key, "/api/v1/roads/bomb?name=Bomb", bomb);
  expect_import_limit(refused, "max_osm_decompressed_bytes");
  EXPECT_NE(refused.body.find("max_osm_decompressed_bytes = 268435456"), std::string::npos) << refused.body;
  // Inflating 256 MiB into a spool file: ~0.5 s of CPU, some more of disk writes.
  const double ms = ms_since(t0);
  EXPECT_LT(ms, 20000 * kSlow);
  std::printf("[bomb] 2 GiB gzip bomb (%zu bytes) refused in %.0f ms\n", bomb.size(), ms);
  probe.expect_fast("H2 gzip bomb");
  EXPECT_EQ(live.get("/api/v1/roads/bomb").status, 404);
}

// After DELETE, re-uploading the same bytes imports again (it answered skipped: true, and the
// city stayed missing).
TEST(Hostile, DeletedDataCanBeImportedAgainFromTheSameBytes) {
  LiveServer live;
  const auto key = create_key(live);
  const auto loom = file_bytes(data_file("metro/loom_freiburg.json"));
  ASSERT_EQ(put(live, key, "/api/v1/cities/freiburg/metro?name=Freiburg", loom).status, 200);
  ASSERT_EQ(http_request(live.port(), "DELETE", "/api/v1/cities/freiburg", bearer(key)).status, 200);
  const auto again = put(live, key, "/api/v1/cities/freiburg/metro?name=Freiburg", loom);
  ASSERT_EQ(again.status, 200) << again.body;
  EXPECT_EQ(nlohmann::json::parse(again.body)["skipped"], false);
  EXPECT_EQ(live.get("/api/v1/cities/freiburg").status, 200);
}

// Focus polygons: every road edge is tested against every region, so their vertices share one
// budget (32 polygons of 2,150 vertices took 3.65 s on Liechtenstein).
TEST(Hostile, FocusPolygonsShareOneVertexBudget) {
  LiveServer live;
  auto ring = [](double lon, double lat, double r, int n) {
    nlohmann::json pts = nlohmann::json::array();
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n;
      pts.push_back({std::round((lon + r * std::cos(a)) * 1e7) / 1e7, std::round((lat + r * std::sin(a)) * 1e7) / 1e7});
    }
    return pts;
  };
  auto focus = [&](int polygons) {
    nlohmann::json body = {{"roads", "monaco"}, {"output", {{"roads", "none"}}}, {"regions", nlohmann::json::array()}};
    for (int k = 0; k < polygons; ++k)
      body["regions"].push_back({{"polygon", ring(7.42, 43.735, 0.02 + 0.001 * k, 2150)}, {"scale", 2}});
    return http_request(live.port(), "POST", "/api/v1/deform/focus", {{"Content-Type", "application/json"}}, body.dump());
  };
  CheapReadProbe probe(live.port());
  const auto refused = focus(5);  // 10,750 vertices
  EXPECT_EQ(refused.status, 413) << refused.body.substr(0, 300);
  EXPECT_EQ(error_of(refused)["field"], "regions");
  const auto t0 = Clock::now();
  const auto within = focus(4);  // 8,600 vertices, each polygon over the whole of Monaco
  EXPECT_EQ(within.status, 200) << within.body.substr(0, 300);
  EXPECT_LT(ms_since(t0), 2000 * kSlow);
  probe.expect_fast("focus polygons");
}

// --- unbounded shared state ---

TEST(Hostile, UnknownMethodsShareOneMetricsSeries) {
  LiveServer live({"--rate-limit", "0"});
  const std::size_t before = live.get("/metrics").body.size();
  for (int i = 0; i < 300; ++i) {
    std::string method = "M";
    method.append(std::to_string(i * 7919)).append("X");
    exchange(live.port(), method + " /api/v1/cities HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", 2s);
  }
  const auto metrics = live.get("/metrics").body;
  EXPECT_EQ(metrics.find("M7919X"), std::string::npos) << "a client's method became a label value";
  EXPECT_NE(metrics.find("method=\"other\""), std::string::npos);
  EXPECT_LT(metrics.size(), before + 8192) << "the metrics grew by " << metrics.size() - before << " bytes";
}

TEST(Hostile, StaleUploadDirectoriesAreRemovedAtStart) {
  TempDir tmp;
  // A dead process's upload directory (a server killed during an upload) and a live one's.
  const pid_t dead = fork();
  if (dead == 0) _exit(0);
  waitpid(dead, nullptr, 0);
  const auto stale = tmp.path() / ("tourmap-upload-" + std::to_string(dead) + "-AbC123");
  const auto alive = tmp.path() / ("tourmap-upload-" + std::to_string(getpid()) + "-XyZ789");
  std::filesystem::create_directories(stale);
  std::filesystem::create_directories(alive);
  std::ofstream(stale / "london.osm.pbf") << std::string(1 << 20, 'x');
  const char* previous = std::getenv("TMPDIR");
  const std::string saved = previous ? previous : "";
  setenv("TMPDIR", tmp.path().c_str(), 1);
  LiveServer live;
  if (previous) setenv("TMPDIR", saved.c_str(), 1); else unsetenv("TMPDIR");
  EXPECT_FALSE(std::filesystem::exists(stale)) << "the dead server's upload was left behind";
  EXPECT_TRUE(std::filesystem::exists(alive)) << "a running process's upload was removed";
}

TEST(Hostile, AcceptBacksOffWhenOutOfDescriptors) {
#if defined(TOURMAP_SANITIZED)
  // UBSan checks dynamic types by probing memory through a pipe (sanitizer_common's
  // IsAccessibleMemoryRange); with no descriptor left that fails, and every virtual call is
  // reported as undefined behaviour. The release build runs this test.
  GTEST_SKIP() << "needs free file descriptors in the sanitizer runtime";
#endif
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_NOFILE, &saved), 0);
  rlimit low = saved;
  low.rlim_cur = 96;
  ASSERT_EQ(setrlimit(RLIMIT_NOFILE, &low), 0);  // inherited by the server only: restored below
  std::unique_ptr<LiveServer> live;
  try {
    live = std::make_unique<LiveServer>(std::vector<std::string>{"--rate-limit", "0"});
  } catch (...) {
    setrlimit(RLIMIT_NOFILE, &saved);
    throw;
  }
  ASSERT_EQ(setrlimit(RLIMIT_NOFILE, &saved), 0);
  std::vector<int> held;
  for (int i = 0; i < 150; ++i) {
    const int fd = connect_to(live->port());  // the listen backlog takes them; accept runs dry
    if (fd >= 0) held.push_back(fd);
  }
  std::this_thread::sleep_for(300ms);
  const double cpu_before = cpu_seconds(live->server->pid());
  std::this_thread::sleep_for(2s);
  const double cpu = cpu_seconds(live->server->pid()) - cpu_before;
  EXPECT_LT(cpu, 0.4) << "the accept loop spins while out of descriptors: " << cpu << " s of CPU in 2 s";
  for (int fd : held) ::close(fd);
  const auto t0 = Clock::now();
  int status = 0;
  while (ms_since(t0) < 15000 && (status = live->get("/healthz").status) != 200) std::this_thread::sleep_for(100ms);
  EXPECT_EQ(status, 200) << "the server does not accept again once descriptors are free";
}

// --- minor ---

TEST(Hostile, NulBytesDoNotTruncateErrorMessages) {
  LiveServer live;
  const auto r = http_request(live.port(), "POST", "/api/v1/deform/focus", {{"Content-Type", "application/json"}},
                              R"({"roads":"monaco","grid":{"kind":"adap\u0000tive"},"regions":[]})");
  ASSERT_EQ(r.status, 400) << r.body;
  const std::string message = error_of(r)["message"];
  EXPECT_NE(message.find("'adap\\x00tive' is not one of adaptive, uniform, edges"), std::string::npos) << message;
  EXPECT_EQ(message.rfind("grid.kind: ", 0), 0u) << message;
}

TEST(Hostile, WholeWorldWindowFindsClusters) {
  LiveServer live;
  const auto world = live.get_json("/api/v1/cities/vienna/clusters?bbox=-180,-90,180,90");
  EXPECT_GT(world["clusters"].size(), 0u) << world.dump();
  const auto city = live.get_json("/api/v1/cities/vienna/clusters");
  EXPECT_EQ(world["clusters"], city["clusters"]) << "the world window and the city's own differ";
}

TEST(Hostile, GridLimitsAreTheDocumentedUnknowns) {
  LiveServer live;
  auto post = [&](const std::string& body) {
    return http_request(live.port(), "POST", "/api/v1/deform/focus", {{"Content-Type", "application/json"}}, body);
  };
  // A uniform grid of 200 cells along the longer side: beyond the Cholesky solver's limit, which
  // the message states in unknowns (2 per grid vertex), the unit the documentation uses.
  const auto r = post(R"({"roads":"monaco","grid":{"kind":"uniform","n":200},"solver":"cholesky",
                          "regions":[{"center":[7.42,43.735],"radius_m":300,"scale":2}],"output":{"roads":"none"}})");
  ASSERT_EQ(r.status, 413) << r.body;
  const std::string message = error_of(r)["message"];
  std::smatch m;
  ASSERT_TRUE(std::regex_search(message, m, std::regex(R"((\d+) grid vertices \((\d+) unknowns\) exceed the limit of (\d+) unknowns)")))
      << message;
  EXPECT_EQ(std::stol(m[2]), 2 * std::stol(m[1]));
  EXPECT_GT(std::stol(m[2]), std::stol(m[3]));
  EXPECT_EQ(m[3], "60000");
  const auto spec = live.get("/api/v1/openapi.yaml").body;
  EXPECT_NE(spec.find("at most 60,000 unknowns for a grid solved by Cholesky"), std::string::npos)
      << "the documented limit differs from the enforced one";
}

}  // namespace
}  // namespace tourmap::test
