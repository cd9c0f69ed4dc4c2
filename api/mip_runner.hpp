#pragma once
// Runs a MIP in a child process (`tourmap solve-mip`) and kills it at the deadline: CBC does
// not honour its own time limit during the root LP (a 60 s limit ran 204 s on these machines),
// and a thread cannot be stopped safely. posix_spawn is safe from a multi-threaded server.

#include "metro/mip_model.hpp"

#include <functional>
#include <string>

namespace tourmap::api {

using MipSolver = std::function<metro::MipResult(const metro::MipModel&, double time_limit_s, double gap)>;

// How the child's overrun is measured. wall: a client waits for the answer, so the child is
// killed `grace_s` of wall time past its limit. cpu: nobody waits (background improvements at
// nice 10), so it is killed once it has used `grace_s` of CPU time past its limit: CBC's own
// limit is CPU time too, and on a busy machine a low-priority child gets little CPU, so a wall
// deadline there would kill every solve under load. A wall backstop of 20x (limit + grace)
// still bounds a child that gets no CPU at all.
enum class ChildClock { wall, cpu };

// A solver that spawns `executable solve-mip`; the child gets `time_limit_s` for CBC and is
// killed `grace_s` later (by `clock`) if still running (status "killed").
MipSolver child_process_mip_solver(std::string executable, double grace_s = 1.0, ChildClock clock = ChildClock::wall);

// The child's side: reads a model from stdin, solves it with CBC, writes the result to stdout.
int solve_mip_from_stdin(double time_limit_s, double gap);

}  // namespace tourmap::api
