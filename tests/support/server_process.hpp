#pragma once
// Runs the real `tourmap` binary as a child process: imports, and `serve --port 0` with the
// port read from its first line of output. Stops it with SIGTERM (then SIGKILL) on destruction.

#include <atomic>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace tourmap::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs a command to completion.
CommandResult run_command(const std::vector<std::string>& argv);

class ServerProcess {
 public:
  // Starts `binary serve --db db --port 0 ...extra`; throws if it does not come up in 20 s.
  ServerProcess(const std::string& binary, const std::string& db, const std::vector<std::string>& extra = {});
  ~ServerProcess();
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  unsigned short port() const { return port_; }
  int pid() const { return pid_; }
  // Sends SIGTERM and waits; returns the exit status and everything the server printed.
  CommandResult stop(int timeout_s = 20);
  // For a test that finds the server unresponsive: what each of its threads is doing (name,
  // state, kernel wait channel; the stacks too where gdb is installed and may attach) and
  // the end of what it printed.
  std::string diagnose() const;

 private:
  void drain();  // the reader thread: keeps the output pipe empty so the server never blocks on it

  int pid_ = -1;
  int out_fd_ = -1;
  unsigned short port_ = 0;
  mutable std::mutex output_mutex_;
  std::string output_;
  std::atomic<bool> stop_draining_{false};
  std::thread reader_;
};

}  // namespace tourmap::test
