#include "mip_runner.hpp"

#include "util/stop.hpp"

#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <iterator>
#include <sstream>

extern char** environ;

namespace tourmap::api {
namespace {

bool write_all(int fd, const std::string& data) {
  std::size_t done = 0;
  while (done < data.size()) {
    ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// The CPU seconds (user + system) process `pid` has used, from /proc/PID/stat (fields 14 and 15,
// in clock ticks, after the command name in parentheses); -1 when it cannot be read.
double process_cpu_seconds(pid_t pid) {
  char path[64];
  std::snprintf(path, sizeof path, "/proc/%d/stat", static_cast<int>(pid));
  std::FILE* f = std::fopen(path, "r");
  if (!f) return -1;
  char buf[1024];
  const std::size_t n = std::fread(buf, 1, sizeof buf - 1, f);
  std::fclose(f);
  buf[n] = 0;
  const char* p = std::strrchr(buf, ')');
  if (!p) return -1;
  // After ")": state (field 3), then fields 4..13, then utime (14) and stime (15).
  unsigned long long utime = 0, stime = 0;
  if (std::sscanf(p + 1, " %*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %llu %llu", &utime, &stime) != 2) return -1;
  return static_cast<double>(utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

}  // namespace

MipSolver child_process_mip_solver(std::string executable, double grace_s, ChildClock clock) {
  return [executable, grace_s, clock](const metro::MipModel& model, double time_limit_s, double gap) {
    metro::MipResult failed;
    failed.status = "error";
    int in_pipe[2], out_pipe[2];
    if (pipe(in_pipe) != 0) return failed;
    if (pipe(out_pipe) != 0) {
      close(in_pipe[0]);
      close(in_pipe[1]);
      return failed;
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, in_pipe[0], 0);
    posix_spawn_file_actions_adddup2(&actions, out_pipe[1], 1);
    posix_spawn_file_actions_addclose(&actions, in_pipe[1]);
    posix_spawn_file_actions_addclose(&actions, out_pipe[0]);
    char limit[32], gap_text[32];
    std::snprintf(limit, sizeof limit, "%.3f", time_limit_s);
    std::snprintf(gap_text, sizeof gap_text, "%.6f", gap);
    std::vector<std::string> args = {executable, "solve-mip", limit, gap_text};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    int rc = posix_spawn(&pid, executable.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(in_pipe[0]);
    close(out_pipe[1]);
    if (rc != 0) {
      close(in_pipe[1]);
      close(out_pipe[0]);
      return failed;
    }
    // The child reads the whole model before it answers, so writing first cannot deadlock.
    bool written = write_all(in_pipe[1], metro::serialize(model));
    close(in_pipe[1]);
    std::string output;
    const double allowed_s = time_limit_s + grace_s;
    const double wall_s = clock == ChildClock::wall ? allowed_s : 20 * allowed_s;
    auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(static_cast<long long>(wall_s * 1000));
    // The request's own deadline and client (util/stop.hpp): a solve nobody waits for is killed.
    const util::StopToken* stop = util::current_stop();
    bool killed = false, stopped = false;
    while (written) {
      auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
      stopped = stop && stop->stop_requested();
      const bool over_cpu = clock == ChildClock::cpu && process_cpu_seconds(pid) > allowed_s;
      if (left <= 0 || stopped || over_cpu) {
        kill(pid, SIGKILL);
        killed = true;
        break;
      }
      pollfd p{out_pipe[0], POLLIN, 0};
      if (poll(&p, 1, static_cast<int>(std::min<long long>(left, 200))) <= 0) continue;
      char buf[65536];
      ssize_t n = read(out_pipe[0], buf, sizeof buf);
      if (n <= 0) break;  // the child is done
      output.append(buf, static_cast<std::size_t>(n));
    }
    if (!written) kill(pid, SIGKILL);
    close(out_pipe[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    if (stopped) util::check_stop();  // throws util::Stopped
    if (killed) {
      metro::MipResult r;
      r.status = "killed";
      return r;
    }
    try {
      return metro::deserialize_result(output);
    } catch (const std::exception&) {
      return failed;
    }
  };
}

int solve_mip_from_stdin(double time_limit_s, double gap) {
  std::ostringstream in;
  in << std::cin.rdbuf();
  auto model = metro::deserialize_model(in.str());
  auto result = metro::solve_with_cbc(model, time_limit_s, gap);
  auto bytes = metro::serialize(result);
  std::fwrite(bytes.data(), 1, bytes.size(), stdout);
  std::fflush(stdout);
  return 0;
}

}  // namespace tourmap::api
