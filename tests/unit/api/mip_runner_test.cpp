// The child-process MIP solver's deadlines, with stand-in children (shell scripts) instead of
// `tourmap solve-mip`: one that sleeps (no CPU) and one that spins (all CPU).

#include "api/mip_runner.hpp"

#include "temp_dir.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <string>

namespace tourmap::api {
namespace {

using Clock = std::chrono::steady_clock;

// An executable script in `dir` running `body` (its arguments are ignored).
std::string script(const test::TempDir& dir, const std::string& name, const std::string& body) {
  const auto path = dir.write(name, "#!/bin/sh\n" + body + "\n");
  chmod(path.c_str(), 0755);
  return path;
}

struct Run {
  metro::MipResult result;
  double seconds = 0;
};

Run solve(const MipSolver& solver, double limit_s) {
  metro::MipModel model;
  const auto started = Clock::now();
  Run r;
  r.result = solver(model, limit_s, 0.0);
  r.seconds = std::chrono::duration<double>(Clock::now() - started).count();
  return r;
}

TEST(ChildProcessMipSolver, WallClockKillsASleepingChildAtItsDeadline) {
  test::TempDir dir;
  const auto sleeper = script(dir, "sleeper", "cat > /dev/null; exec sleep 30");
  const auto run = solve(child_process_mip_solver(sleeper, 0.2, ChildClock::wall), 0.1);
  EXPECT_EQ(run.result.status, "killed");
  EXPECT_LT(run.seconds, 5.0);
}

// A child that is waiting, not computing, uses no CPU: the CPU clock lets it be (a starved
// background solve is not killed for the machine being busy) until the wall backstop, 20x
// (limit + grace).
TEST(ChildProcessMipSolver, CpuClockLetsAWaitingChildFinish) {
  test::TempDir dir;
  const auto late = script(dir, "late", "cat > /dev/null; sleep 1; printf 'not a result'");
  const auto run = solve(child_process_mip_solver(late, 0.1, ChildClock::cpu), 0.1);
  EXPECT_EQ(run.result.status, "error");  // it answered (nonsense), it was not killed
  EXPECT_GE(run.seconds, 1.0);
  const auto backstop = solve(child_process_mip_solver(script(dir, "sleeper", "cat > /dev/null; exec sleep 30"), 0.05,
                                                       ChildClock::cpu),
                              0.05);
  EXPECT_EQ(backstop.result.status, "killed");
  EXPECT_LT(backstop.seconds, 10.0);  // 20 x 0.1 s = 2 s
}

TEST(ChildProcessMipSolver, CpuClockKillsASpinningChildOnceItsCpuTimeIsUsed) {
  test::TempDir dir;
  const auto spinner = script(dir, "spinner", "cat > /dev/null; while :; do :; done");
  const auto run = solve(child_process_mip_solver(spinner, 0.2, ChildClock::cpu), 0.1);
  EXPECT_EQ(run.result.status, "killed");
  EXPECT_LT(run.seconds, 6.0);  // 0.3 s of CPU; the wall backstop would be 6 s
}

}  // namespace
}  // namespace tourmap::api
