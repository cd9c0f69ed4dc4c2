// Scale-out failover (ctest scale_nginx_failover): two `tourmap serve` processes share one SQLite
// database (the sample manifest, imported once) behind a local nginx configured from
// docker/nginx.conf.template, the template docker/compose.yaml uses. Client threads send a
// steady mix of GETs through nginx; halfway, one tourmap process gets SIGKILL.
//
// Passes when no request failed after at most one client retry, both processes served traffic
// before the kill, the survivor after it, and a WebSocket to /api/v1/events upgrades through
// nginx before and after the kill. Prints counts per upstream from nginx's access log.
//
//   build/tests/scale/scale_nginx_failover [--seconds 12] [--clients 6] [--rate 300] [--keep]
//                                          [--template docker/nginx.conf.template]
//
// Exit 0 pass, 1 fail, 77 skipped (no nginx; scripts/setup installs it). nginx runs as the
// current user with every path in a temporary directory. Every child runs in its own process
// group, gets SIGKILL (nginx: SIGTERM) if this process dies (PR_SET_PDEATHSIG) and is stopped on
// every exit path; SIGINT/SIGTERM/SIGHUP kill them too (the temporary directory stays then).

#include "http_client.hpp"
#include "server_process.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

constexpr int kSkip = 77;

// ---- child processes -----------------------------------------------------------------------

// Process groups to kill from a signal handler (async-signal-safe: a fixed array of atomics).
std::atomic<pid_t> g_groups[8];

void register_group(pid_t pid) {
  for (auto& g : g_groups) {
    pid_t expected = 0;
    if (g.compare_exchange_strong(expected, pid)) return;
  }
}
void unregister_group(pid_t pid) {
  for (auto& g : g_groups) {
    pid_t expected = pid;
    g.compare_exchange_strong(expected, 0);
  }
}

extern "C" void on_fatal_signal(int sig) {
  for (auto& g : g_groups) {
    pid_t pid = g.load();
    if (pid > 0) kill(-pid, SIGKILL);
  }
  signal(sig, SIG_DFL);
  raise(sig);
}

// A child in its own process group with stdout and stderr in `log_file`; stopped (the whole
// group) on destruction. It gets `parent_death_signal` when this process dies: SIGKILL for a
// single process; SIGTERM for nginx, whose master then stops its workers (SIGKILL would orphan
// them).
class Child {
 public:
  Child(std::string name, const std::vector<std::string>& argv, const std::string& log_file,
        int parent_death_signal = SIGKILL)
      : name_(std::move(name)), log_(log_file) {
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    int out = open(log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (out < 0) throw std::runtime_error("cannot open " + log_file);
    pid_t parent = getpid();
    pid_ = fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
      setpgid(0, 0);
      prctl(PR_SET_PDEATHSIG, parent_death_signal);
      if (getppid() != parent) _exit(127);
      signal(SIGPIPE, SIG_DFL);
      int in = open("/dev/null", O_RDONLY);
      dup2(in, 0);
      dup2(out, 1);
      dup2(out, 2);
      execv(args[0], args.data());
      _exit(127);
    }
    close(out);
    setpgid(pid_, pid_);  // also here: no window in which the child has no group of its own
    register_group(pid_);
  }
  ~Child() { stop(SIGTERM, 5s); }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  pid_t pid() const { return pid_; }
  const std::string& name() const { return name_; }
  const std::string& log_file() const { return log_; }
  bool running() {
    if (pid_ <= 0) return false;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      reaped(status);
      return false;
    }
    return true;
  }
  // Exit status as a string ("exit 0", "signal 9"), once the child is gone.
  const std::string& how_it_ended() const { return ended_; }

  // `sig` to the whole group, then SIGKILL after `grace`; reaps the child.
  void stop(int sig, std::chrono::milliseconds grace) {
    if (pid_ <= 0) return;
    kill(-pid_, sig);
    auto deadline = Clock::now() + grace;
    int status = 0;
    while (true) {
      pid_t r = waitpid(pid_, &status, WNOHANG);
      if (r == pid_ || r < 0) break;
      if (Clock::now() > deadline) {
        kill(-pid_, SIGKILL);
        waitpid(pid_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(20ms);
    }
    kill(-pid_, SIGKILL);  // stragglers in the group (nginx workers); ESRCH when none
    reaped(status);
  }
  // SIGKILL to this process alone, as a crash would.
  void crash() {
    int status = 0;
    kill(pid_, SIGKILL);
    waitpid(pid_, &status, 0);
    reaped(status);
  }

 private:
  void reaped(int status) {
    ended_ = WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                               : "signal " + std::to_string(WTERMSIG(status));
    unregister_group(pid_);
    pid_ = -1;
  }
  std::string name_;
  std::string log_;
  pid_t pid_ = -1;
  std::string ended_;
};

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string tail(const std::string& text, std::size_t n = 3000) {
  return text.size() <= n ? text : "..." + text.substr(text.size() - n);
}

// Waits for `tourmap serve --port 0` to print its port.
unsigned short wait_listening(Child& server) {
  std::regex listening(R"(listening on http://[^:\s]+:(\d+))");
  auto deadline = Clock::now() + 20s;
  while (Clock::now() < deadline) {
    std::smatch m;
    std::string out = read_file(server.log_file());
    if (std::regex_search(out, m, listening)) return static_cast<unsigned short>(std::stoi(m[1]));
    if (!server.running())
      throw std::runtime_error(server.name() + " exited (" + server.how_it_ended() + "):\n" + tail(out));
    std::this_thread::sleep_for(50ms);
  }
  throw std::runtime_error(server.name() + " did not start in 20 s:\n" + tail(read_file(server.log_file())));
}

unsigned short free_port() {
  int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  if (s < 0 || bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      getsockname(s, reinterpret_cast<sockaddr*>(&a), &len) != 0)
    throw std::runtime_error("cannot find a free port");
  close(s);
  return ntohs(a.sin_port);
}

std::optional<std::string> find_nginx() {
  if (const char* env = std::getenv("NGINX"); env && *env) {  // an explicit choice, or none
    if (access(env, X_OK) == 0) return std::string(env);
    return std::nullopt;
  }
  std::vector<std::string> dirs;
  if (const char* path = std::getenv("PATH")) {
    std::stringstream s(path);
    for (std::string d; std::getline(s, d, ':');)
      if (!d.empty()) dirs.push_back(d);
  }
  for (const char* d : {"/usr/sbin", "/usr/local/sbin", "/sbin", "/usr/local/nginx/sbin"}) dirs.push_back(d);
  for (const auto& d : dirs) {
    std::string p = d + "/nginx";
    if (access(p.c_str(), X_OK) == 0) return p;
  }
  return std::nullopt;
}

// ---- the template --------------------------------------------------------------------------

// Fills in docker/nginx.conf.template: `${NAME}` from `vars`; a line holding ${TOURMAP_UPSTREAM}
// once per upstream. Throws on a placeholder it does not know (the template and this test must
// not drift apart).
std::string render_template(const std::string& text, const std::map<std::string, std::string>& vars,
                            const std::vector<std::string>& upstreams) {
  const std::string upstream_key = "${TOURMAP_UPSTREAM}";
  auto replace_all = [](std::string s, const std::string& from, const std::string& to) {
    for (auto pos = s.find(from); pos != std::string::npos; pos = s.find(from, pos + to.size()))
      s.replace(pos, from.size(), to);
    return s;
  };
  std::string out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    for (const auto& [name, value] : vars) line = replace_all(line, "${" + name + "}", value);
    if (line.find(upstream_key) != std::string::npos) {
      for (const auto& u : upstreams) out += replace_all(line, upstream_key, u) + "\n";
    } else {
      out += line + "\n";
    }
  }
  if (auto pos = out.find("${TOURMAP_"); pos != std::string::npos)
    throw std::runtime_error("template placeholder this test does not fill: " + out.substr(pos, 40));
  return out;
}

// ---- HTTP client with keep-alive and timeouts ------------------------------------------------

class KeepAliveClient {
 public:
  explicit KeepAliveClient(unsigned short port) : port_(port) {}

  // GET through one persistent connection (reconnects when closed). Returns the status and the
  // body size; throws on connection errors and timeouts (after which it reconnects).
  int get(const std::string& target, std::size_t* body_bytes) {
    if (!stream_) {
      stream_.emplace(ioc_);
      run([&](auto done) {
        stream_->async_connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port_), done);
      });
    }
    http::request<http::empty_body> req{http::verb::get, target, 11};
    req.set(http::field::host, "127.0.0.1:" + std::to_string(port_));
    req.set(http::field::accept_encoding, "gzip");
    req.keep_alive(true);
    run([&](auto done) { http::async_write(*stream_, req, done); });
    http::response_parser<http::string_body> parser;
    parser.body_limit(64u << 20);
    run([&](auto done) { http::async_read(*stream_, buffer_, parser, done); });
    auto res = parser.release();
    if (body_bytes) *body_bytes = res.body().size();
    if (!res.keep_alive()) reset();
    return static_cast<int>(res.result_int());
  }
  void reset() {
    if (stream_) {
      beast::error_code ec;
      stream_->socket().shutdown(tcp::socket::shutdown_both, ec);
      stream_->close();
    }
    stream_.reset();
    buffer_.clear();
  }

 private:
  template <class Start>
  void run(Start start) {
    beast::error_code ec;
    stream_->expires_after(10s);
    start([&ec](beast::error_code e, auto&&...) { ec = e; });
    ioc_.restart();
    ioc_.run();
    if (ec) {
      reset();
      throw beast::system_error(ec);
    }
  }
  unsigned short port_;
  net::io_context ioc_;
  std::optional<beast::tcp_stream> stream_;
  beast::flat_buffer buffer_;
};

// ---- the load ------------------------------------------------------------------------------

// A steady read mix over the sample data: city list and details, metro GeoJSON, clusters, POIs,
// road networks by bbox.
const std::vector<std::string> kTargets = {
    "/api/v1/cities",
    "/api/v1/cities/vienna",
    "/api/v1/cities/vienna/metro?bbox=16.3,48.17,16.42,48.24",
    "/api/v1/cities/berlin/metro",
    "/api/v1/cities/london/clusters?bbox=-0.2,51.45,0.0,51.55",
    "/api/v1/cities/vienna/clusters?bbox=16.3,48.17,16.42,48.24",
    "/api/v1/cities/berlin/pois?bbox=13.3,52.48,13.45,52.55&limit=50",
    "/api/v1/cities/london/pois?limit=100",
    "/api/v1/roads",
    "/api/v1/roads/monaco?bbox=7.41,43.72,7.43,43.74",
    "/api/v1/roads/west-oakland?bbox=-122.30,37.80,-122.28,37.82",
    "/api/v1/cities/lisbon/metro",
};

struct LoadStats {
  std::atomic<long> total{0};    // requests (a retried one counts once)
  std::atomic<long> retried{0};  // requests whose first attempt failed
  std::atomic<long> failed{0};   // requests whose retry failed too
  std::atomic<long> bytes{0};
  std::mutex mutex;
  std::vector<std::string> failures;  // the first few, for the report
  void note(const std::string& what) {
    std::lock_guard lock(mutex);
    if (failures.size() < 10) failures.push_back(what);
  }
};

void client_loop(unsigned short port, int index, std::chrono::microseconds interval,
                 const std::atomic<bool>& stop, LoadStats& stats) {
  KeepAliveClient client(port);
  std::size_t next = static_cast<std::size_t>(index) * 5;
  auto tick = Clock::now() + interval * index / 8;
  while (!stop.load()) {
    std::this_thread::sleep_until(tick);
    tick += interval;
    const std::string& target = kTargets[next++ % kTargets.size()];
    std::string first_error;
    bool ok = false;
    for (int attempt = 0; attempt < 2 && !ok; ++attempt) {
      try {
        std::size_t bytes = 0;
        int status = client.get(target, &bytes);
        if (status == 200 && bytes > 0) {
          ok = true;
          stats.bytes += static_cast<long>(bytes);
        } else {
          client.reset();
          first_error = "HTTP " + std::to_string(status);
        }
      } catch (const std::exception& e) {
        first_error = e.what();
      }
      if (!ok && attempt == 0) {
        ++stats.retried;
        stats.note("retried " + target + ": " + first_error);
      }
    }
    ++stats.total;
    if (!ok) {
      ++stats.failed;
      stats.note("FAILED " + target + ": " + first_error);
    }
  }
}

// ---- WebSocket through nginx -----------------------------------------------------------------

// /api/v1/events upgrades, says hello, answers a ping. Returns "" or what went wrong.
std::string check_events_websocket(unsigned short port) {
  try {
    tourmap::test::WsClient ws(port, "/api/v1/events");
    std::string hello = ws.receive(5s);
    if (hello.find("\"type\":\"hello\"") == std::string::npos) return "no hello: " + hello;
    ws.send(R"({"type":"ping"})");
    std::string pong = ws.receive(5s);
    if (pong.find("\"type\":\"pong\"") == std::string::npos) return "no pong: " + pong;
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

// ---- nginx's access log ----------------------------------------------------------------------

struct LogCounts {
  std::map<std::string, long> before;  // final upstream of load requests before the kill
  std::map<std::string, long> after;   // ... and after it
  long nginx_retries = 0;              // requests nginx passed to more than one upstream
  long non_200 = 0;
  long lines = 0;
};

LogCounts parse_access_log(const std::string& path, double kill_epoch_s, double load_start_epoch_s) {
  // '$msec $remote_addr "$request" $status $body_bytes_sent rt=... upstream="..." ustatus="..." ...'
  std::regex line_re(R"re(^(\S+) \S+ "GET (/api/v1/\S*) [^"]*" (\d+) \d+ rt=\S+ upstream="([^"]*)")re");
  LogCounts c;
  std::istringstream in(read_file(path));
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, line_re)) continue;
    double t = std::stod(m[1]);
    std::string target = m[2];
    if (t < load_start_epoch_s || target == "/api/v1/events") continue;
    ++c.lines;
    if (m[3] != "200") ++c.non_200;
    std::string ups = m[4];
    if (ups.find(',') != std::string::npos) ++c.nginx_retries;
    auto last = ups.rfind(", ");
    std::string final_upstream = last == std::string::npos ? ups : ups.substr(last + 2);
    (t < kill_epoch_s ? c.before : c.after)[final_upstream]++;
  }
  return c;
}

double epoch_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

struct Options {
  int seconds = 12;
  int clients = 6;
  int rate = 300;  // requests per second, all clients together
  bool keep = false;
  std::string template_file = TOURMAP_NGINX_TEMPLATE;
};

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> int {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return std::stoi(argv[++i]);
    };
    if (a == "--seconds") o.seconds = value();
    else if (a == "--clients") o.clients = value();
    else if (a == "--rate") o.rate = value();
    else if (a == "--keep") o.keep = true;
    else if (a == "--template" && i + 1 < argc) o.template_file = argv[++i];
    else throw std::runtime_error("usage: scale_nginx_failover [--seconds N] [--clients N] [--rate N] [--keep] [--template FILE]");
  }
  if (o.seconds < 4 || o.clients < 1 || o.rate < o.clients) throw std::runtime_error("bad option values");
  return o;
}

int run(const Options& opt) {
  auto nginx = find_nginx();
  if (!nginx) {
    std::printf("SKIP: nginx is not installed (scripts/setup installs it)\n");
    return kSkip;
  }

  tourmap::test::TempDir dir;
  // nginx started as root runs its workers as nobody: they must reach the temp directories.
  chmod(dir.path().c_str(), 0755);
  std::printf("temp dir %s%s\n", dir.path().c_str(), opt.keep ? " (kept)" : "");

  // One database, imported once with the sample manifest.
  const std::string db = dir.file("tourmap.db");
  auto t0 = Clock::now();
  auto imported = tourmap::test::run_command(
      {TOURMAP_BIN, "import", "manifest", TOURMAP_MANIFEST, "--data-dir", tourmap::test::data_dir(), "--db", db});
  if (imported.exit_code != 0) throw std::runtime_error("import failed:\n" + tail(imported.output));
  std::printf("import: sample manifest in %.1f s\n", std::chrono::duration<double>(Clock::now() - t0).count());

  dir.write("web/index.html", "<!doctype html><title>tourmap</title>");
  std::vector<std::unique_ptr<Child>> servers;
  for (const char* name : {"a", "b"}) {
    servers.push_back(std::make_unique<Child>(
        std::string("tourmap-") + name,
        std::vector<std::string>{TOURMAP_BIN, "serve", "--db", db, "--host", "127.0.0.1", "--port", "0",
                                 "--web-root", dir.file("web"), "--data-dir", tourmap::test::data_dir(),
                                 // The six load clients stand for six travellers but share one
                                 // address here, so the per-address caps (tested by the rate-limit
                                 // suite) are off: a 429 would measure the caps, not the failover.
                                 "--rate-limit", "0", "--max-compute-per-client", "0",
                                 "--max-reads-per-client", "0", "--access-log", "off"},
        dir.file(std::string("tourmap-") + name + ".log")));
  }
  std::vector<std::string> upstreams;
  for (auto& s : servers) upstreams.push_back("127.0.0.1:" + std::to_string(wait_listening(*s)));

  // nginx from the template compose uses, on a free port, every path in the temp directory.
  const auto prefix = dir.path() / "nginx";
  std::filesystem::create_directories(prefix / "temp");
  chmod(prefix.c_str(), 0755);
  chmod((prefix / "temp").c_str(), 0755);
  const unsigned short port = free_port();
  const std::string access_log = (prefix / "access.log").string();
  const std::string error_log = (prefix / "error.log").string();
  const std::string conf = (prefix / "nginx.conf").string();
  dir.write("nginx/nginx.conf",
            render_template(read_file(opt.template_file),
                            {{"TOURMAP_NGINX_LISTEN", "127.0.0.1:" + std::to_string(port)},
                             {"TOURMAP_NGINX_TEMP", (prefix / "temp").string()},
                             {"TOURMAP_NGINX_ACCESS_LOG", access_log}},
                            upstreams));
  const std::string globals = "daemon off; pid " + (prefix / "nginx.pid").string() + ";";
  std::vector<std::string> nginx_argv = {*nginx, "-p", prefix.string(), "-c", conf, "-e", error_log, "-g", globals};
  {
    auto args = nginx_argv;
    args.insert(args.begin() + 1, "-t");
    auto checked = tourmap::test::run_command(args);
    if (checked.exit_code != 0)
      throw std::runtime_error("nginx -t rejects the rendered template:\n" + checked.output);
  }
  Child proxy("nginx", nginx_argv, (prefix / "stderr.log").string(), SIGTERM);
  {
    auto deadline = Clock::now() + 10s;
    while (true) {
      try {
        KeepAliveClient probe(port);
        if (probe.get("/healthz", nullptr) == 200) break;
      } catch (const std::exception&) {
      }
      if (!proxy.running() || Clock::now() > deadline)
        throw std::runtime_error("nginx did not come up (" + proxy.how_it_ended() + "):\n" +
                                 tail(read_file(error_log)) + tail(read_file((prefix / "stderr.log").string())));
      std::this_thread::sleep_for(50ms);
    }
  }
  std::printf("nginx %s on 127.0.0.1:%u in front of %s and %s\n", nginx->c_str(), port, upstreams[0].c_str(),
              upstreams[1].c_str());

  std::vector<std::string> problems;
  if (auto err = check_events_websocket(port); !err.empty())
    problems.push_back("WebSocket /api/v1/events through nginx (both up): " + err);

  // The load; halfway, SIGKILL to the first server.
  LoadStats stats;
  std::atomic<bool> stop{false};
  auto interval = std::chrono::microseconds(1'000'000LL * opt.clients / opt.rate);
  const double load_start = epoch_now();
  std::vector<std::thread> clients;
  for (int i = 0; i < opt.clients; ++i)
    clients.emplace_back(client_loop, port, i, interval, std::cref(stop), std::ref(stats));
  std::this_thread::sleep_for(std::chrono::milliseconds(opt.seconds * 500));
  const long total_at_kill = stats.total.load();
  const double kill_time = epoch_now();
  Child& victim = *servers[0];
  const std::string victim_addr = upstreams[0], survivor_addr = upstreams[1];
  victim.crash();
  std::printf("killed %s (%s) after %d s: %s\n", victim.name().c_str(), victim_addr.c_str(), opt.seconds / 2,
              victim.how_it_ended().c_str());
  std::this_thread::sleep_for(std::chrono::milliseconds(opt.seconds * 500));
  stop = true;
  for (auto& t : clients) t.join();

  if (auto err = check_events_websocket(port); !err.empty())
    problems.push_back("WebSocket /api/v1/events through nginx (one killed): " + err);

  if (!servers[1]->running()) problems.push_back("the surviving server exited: " + servers[1]->how_it_ended());
  proxy.stop(SIGQUIT, 5s);  // graceful: the access log is complete
  auto counts = parse_access_log(access_log, kill_time, load_start);

  // Report.
  std::printf("\nload: %d clients, %d req/s target, %d s; SIGKILL to one of two servers at %d s\n", opt.clients,
              opt.rate, opt.seconds, opt.seconds / 2);
  std::printf("  requests %ld (%ld before the kill), retried by the client %ld, failed %ld, %.1f MB received\n",
              stats.total.load(), total_at_kill, stats.retried.load(), stats.failed.load(),
              static_cast<double>(stats.bytes.load()) / 1e6);
  std::printf("  nginx access log: %ld load requests, %ld passed to a second upstream by nginx, %ld not 200\n",
              counts.lines, counts.nginx_retries, counts.non_200);
  std::printf("  %-22s %8s %8s\n", "served by", "before", "after");
  for (const auto& addr : {victim_addr, survivor_addr})
    std::printf("  %-22s %8ld %8ld%s\n", addr.c_str(), counts.before[addr], counts.after[addr],
                addr == victim_addr ? "   (killed)" : "");
  for (const auto& [addr, n] : counts.before)
    if (addr != victim_addr && addr != survivor_addr) std::printf("  %-22s %8ld (before)\n", addr.c_str(), n);
  for (const auto& [addr, n] : counts.after)
    if (addr != victim_addr && addr != survivor_addr) std::printf("  %-22s %8ld (after)\n", addr.c_str(), n);
  for (const auto& f : stats.failures) std::printf("  %s\n", f.c_str());

  if (stats.failed > 0) problems.push_back(std::to_string(stats.failed.load()) + " request(s) failed after a retry");
  if (stats.total < 10L * opt.seconds) problems.push_back("too few requests: " + std::to_string(stats.total.load()));
  if (counts.before[victim_addr] == 0 || counts.before[survivor_addr] == 0)
    problems.push_back("both servers should have served requests before the kill");
  if (counts.after[survivor_addr] == 0) problems.push_back("the survivor served nothing after the kill");
  if (counts.lines < stats.total - stats.failed)
    problems.push_back("nginx logged fewer load requests than the client completed");

  // --keep: move the directory aside before TempDir removes it (the servers may still write logs).
  auto keep_dir = [&] {
    if (!opt.keep) return;
    auto kept = dir.path().string() + "-kept";
    std::filesystem::rename(dir.path(), kept);
    std::filesystem::create_directories(dir.path());
    std::printf("kept %s\n", kept.c_str());
  };
  if (!problems.empty()) {
    std::printf("\nFAIL\n");
    for (const auto& p : problems) std::printf("  - %s\n", p.c_str());
    std::printf("\nnginx error log:\n%s\n", tail(read_file(error_log)).c_str());
    for (auto& s : servers) std::printf("%s output:\n%s\n", s->name().c_str(), tail(read_file(s->log_file())).c_str());
    keep_dir();
    return 1;
  }
  std::printf("\nPASS: no failed requests; both servers served before the kill, the survivor after it; "
              "WebSocket upgrades through nginx before and after\n");
  keep_dir();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  signal(SIGPIPE, SIG_IGN);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) signal(sig, on_fatal_signal);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  try {
    return run(parse_options(argc, argv));
  } catch (const std::exception& e) {
    std::printf("FAIL: %s\n", e.what());
    return 1;
  }
}
