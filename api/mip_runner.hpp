#pragma once
// Runs a MIP in a child process (`tourmap solve-mip`) and kills it at the deadline: CBC does
// not honour its own time limit during the root LP (a 60 s limit ran 204 s on these machines),
// and a thread cannot be stopped safely. posix_spawn is safe from a multi-threaded server.

#include "metro/mip_model.hpp"

#include <functional>
#include <string>

namespace tourmap::api {

using MipSolver = std::function<metro::MipResult(const metro::MipModel&, double time_limit_s, double gap)>;

// A solver that spawns `executable solve-mip`; the child gets `time_limit_s` for CBC and is
// killed `grace_s` later if still running (status "killed").
MipSolver child_process_mip_solver(std::string executable, double grace_s = 1.0);

// The child's side: reads a model from stdin, solves it with CBC, writes the result to stdout.
int solve_mip_from_stdin(double time_limit_s, double gap);

}  // namespace tourmap::api
