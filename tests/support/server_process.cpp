#include "server_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <regex>
#include <stdexcept>
#include <thread>

namespace tourmap::test {
namespace {

// fork + exec with stdout/stderr into a pipe; returns (pid, read end).
std::pair<int, int> spawn(const std::vector<std::string>& argv) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
  pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    dup2(fds[1], 1);
    dup2(fds[1], 2);
    close(fds[0]);
    close(fds[1]);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  close(fds[1]);
  return {pid, fds[0]};
}

// Reads what is available within `timeout_ms`; false at EOF.
bool read_some(int fd, std::string& out, int timeout_ms) {
  pollfd p{fd, POLLIN, 0};
  if (poll(&p, 1, timeout_ms) <= 0) return true;
  char buf[4096];
  ssize_t n = read(fd, buf, sizeof buf);
  if (n <= 0) return false;
  out.append(buf, static_cast<std::size_t>(n));
  return true;
}

int wait_exit(int pid, int timeout_s, int out_fd, std::string& output) {
  auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_s);
  int status = 0;
  while (true) {
    if (out_fd >= 0) read_some(out_fd, output, 20);
    pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      return -9;
    }
    if (out_fd < 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (out_fd >= 0)
    while (read_some(out_fd, output, 0) && output.size() < (1u << 24)) {
    }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

}  // namespace

CommandResult run_command(const std::vector<std::string>& argv) {
  auto [pid, fd] = spawn(argv);
  CommandResult r;
  r.exit_code = wait_exit(pid, 120, fd, r.output);
  close(fd);
  return r;
}

ServerProcess::ServerProcess(const std::string& binary, const std::string& db, const std::vector<std::string>& extra) {
  std::vector<std::string> argv = {binary, "serve", "--db", db, "--port", "0"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  auto [pid, fd] = spawn(argv);
  pid_ = pid;
  out_fd_ = fd;
  std::regex listening(R"(listening on http://[^:]+:(\d+))");
  auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < deadline) {
    if (!read_some(out_fd_, output_, 100)) break;
    std::smatch m;
    if (std::regex_search(output_, m, listening)) {
      port_ = static_cast<unsigned short>(std::stoi(m[1]));
      return;
    }
  }
  stop(5);
  throw std::runtime_error("tourmap serve did not start:\n" + output_);
}

ServerProcess::~ServerProcess() {
  if (pid_ > 0) stop(10);
}

CommandResult ServerProcess::stop(int timeout_s) {
  CommandResult r;
  if (pid_ <= 0) return r;
  kill(pid_, SIGTERM);
  r.exit_code = wait_exit(pid_, timeout_s, out_fd_, output_);
  close(out_fd_);
  pid_ = -1;
  out_fd_ = -1;
  r.output = output_;
  return r;
}

}  // namespace tourmap::test
