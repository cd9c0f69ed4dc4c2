#include "server_process.hpp"

#include <dirent.h>
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
  // What is left in the pipe (not until EOF: a child of the server may still hold it open).
  if (out_fd >= 0)
    for (std::size_t before = output.size() + 1; output.size() != before && output.size() < (1u << 24);) {
      before = output.size();
      if (!read_some(out_fd, output, 0)) break;
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
      reader_ = std::thread([this] { drain(); });
      return;
    }
  }
  stop(5);
  throw std::runtime_error("tourmap serve did not start:\n" + output_);
}

ServerProcess::~ServerProcess() {
  if (pid_ > 0) stop(10);
}

void ServerProcess::drain() {
  std::string chunk;
  while (!stop_draining_) {
    chunk.clear();
    const bool open = read_some(out_fd_, chunk, 100);
    if (!chunk.empty()) {
      std::lock_guard lock(output_mutex_);
      if (output_.size() < (1u << 24)) output_ += chunk;
    }
    if (!open) return;
  }
}

CommandResult ServerProcess::stop(int timeout_s) {
  CommandResult r;
  if (pid_ <= 0) return r;
  kill(pid_, SIGTERM);
  // The reader goes first: wait_exit reads the rest (a MIP child that inherited the pipe may
  // keep it open after the server is gone, so the reader is told to stop, not left to see EOF).
  stop_draining_ = true;
  if (reader_.joinable()) reader_.join();
  std::string output;
  {
    std::lock_guard lock(output_mutex_);
    output = std::move(output_);
  }
  r.exit_code = wait_exit(pid_, timeout_s, out_fd_, output);
  close(out_fd_);
  pid_ = -1;
  out_fd_ = -1;
  r.output = output;
  {
    std::lock_guard lock(output_mutex_);
    output_ = std::move(output);
  }
  return r;
}

namespace {

std::string file_text(const std::string& path) {
  std::string out;
  if (int fd = open(path.c_str(), O_RDONLY); fd >= 0) {
    char buf[4096];
    ssize_t n;
    while ((n = read(fd, buf, sizeof buf)) > 0) out.append(buf, static_cast<std::size_t>(n));
    close(fd);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == 0)) out.pop_back();
  return out;
}

}  // namespace

std::string ServerProcess::diagnose() const {
  if (pid_ <= 0) return "the server is not running";
  std::string out = "server " + std::to_string(pid_) + " threads (name, /proc stat state, wait channel, syscall):\n";
  const std::string task_dir = "/proc/" + std::to_string(pid_) + "/task";
  if (DIR* dir = opendir(task_dir.c_str())) {
    while (dirent* e = readdir(dir)) {
      if (e->d_name[0] == '.') continue;
      const std::string t = task_dir + "/" + e->d_name;
      const auto stat = file_text(t + "/stat");
      const auto close_paren = stat.rfind(')');
      const char state = close_paren != std::string::npos && close_paren + 2 < stat.size() ? stat[close_paren + 2] : '?';
      out += "  " + std::string(e->d_name) + " " + file_text(t + "/comm") + " " + state + " " + file_text(t + "/wchan") +
             " [" + file_text(t + "/syscall") + "]\n";
    }
    closedir(dir);
  }
  // Stacks, where gdb exists and may attach (ptrace rules permitting); bounded in time.
  const auto gdb = run_command({"/usr/bin/timeout", "30", "gdb", "-p", std::to_string(pid_), "-batch", "-nx", "-ex",
                                "thread apply all bt 30"});
  if (gdb.exit_code == 0) out += "stacks:\n" + gdb.output + "\n";
  std::lock_guard lock(output_mutex_);
  out += "the server printed (last 4 KiB):\n" + output_.substr(output_.size() > 4096 ? output_.size() - 4096 : 0);
  return out;
}

}  // namespace tourmap::test
