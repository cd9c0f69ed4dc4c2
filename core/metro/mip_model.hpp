#pragma once
// A mixed-integer program in plain arrays, its byte serialization (so it can be solved in a
// child process that can be killed at the deadline: CBC does not honour its time limit inside
// the root LP), and the CBC solve itself.

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace tourmap::metro {

struct MipModel {
  // Columns.
  std::vector<double> lower, upper, cost;
  std::vector<std::uint8_t> integer;
  // Rows: lo <= sum(coef * x) <= hi.
  struct Row {
    std::vector<std::pair<int, double>> terms;
    double lo, hi;
  };
  std::vector<Row> rows;
  std::vector<double> start;  // a feasible solution (CBC's MIP start); empty for none

  int add_column(double lo, double hi, double c, bool is_integer, double start_value);
  void add_row(std::vector<std::pair<int, double>> terms, double lo, double hi);
  std::size_t columns() const { return lower.size(); }
};

struct MipResult {
  std::string status;  // "optimal", "time_limit", "infeasible", "no_solution", "killed", "error"
  std::vector<double> x;  // empty without a solution
  double objective = 0, bound = 0, gap = 0;  // gap: (objective - bound) / |objective|
};

std::string serialize(const MipModel& m);
MipModel deserialize_model(std::string_view bytes);  // throws std::invalid_argument
std::string serialize(const MipResult& r);
MipResult deserialize_result(std::string_view bytes);

// Solves in this process with CBC (time limit and relative gap; the start is passed on).
MipResult solve_with_cbc(const MipModel& m, double time_limit_s, double relative_gap);

// How a caller has a MIP solved: solve_with_cbc in this process (tests, benchmarks), or in a
// child process it can kill at the deadline (the server, api/mip_runner.hpp).
using MipSolveFn = std::function<MipResult(const MipModel& m, double time_limit_s, double relative_gap)>;

// Largest violation of bounds, rows and integrality by `x` (0 for a feasible solution).
double max_violation(const MipModel& m, const std::vector<double>& x);

}  // namespace tourmap::metro
