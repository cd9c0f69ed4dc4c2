#pragma once
// Linear programs (MipModels without integer columns) solved by CLP in this process. CBC adds
// only its set-up to a pure LP, and that set-up dominated: on the first spacing programs
// (metro/station_spacing.hpp) CBC took 0.5 s on Vienna and 25 s on London where CLP's primal
// simplex took 0.07 s and 2.2 s.

#include "metro/mip_model.hpp"

#include <memory>
#include <utility>
#include <vector>

class ClpSimplex;

namespace tourmap::metro {

// status "optimal", "time_limit", "infeasible" or "error"; x set for "optimal" only. Integer
// marks on columns are ignored (the relaxation is solved). With `m.start` (one value per
// column) primal simplex starts from that point (a values pass: a feasible start skips phase 1).
MipResult solve_lp_with_clp(const MipModel& m, double time_limit_s);

// One LP that grows: solved, then given more columns and rows (cuts: rows that the solution
// turned out to need) and solved again from the last basis, which stays primal or dual
// feasible where a fresh start would begin from nothing.
class LpSession {
 public:
  explicit LpSession(const MipModel& m);
  ~LpSession();
  LpSession(const LpSession&) = delete;
  LpSession& operator=(const LpSession&) = delete;

  // The first solve: primal simplex (from m.start when it has one value per column).
  MipResult solve(double time_limit_s);
  // Columns and rows added since the last solve are in force after the next resolve().
  int add_column(double lo, double hi, double cost);
  void add_row(const std::vector<std::pair<int, double>>& terms, double lo, double hi);
  // Again from the last basis: dual simplex (new rows cut the last solution off).
  MipResult resolve(double time_limit_s);
  std::size_t columns() const;
  std::size_t rows() const;

 private:
  MipResult result() const;
  void flush();
  std::unique_ptr<ClpSimplex> lp_;
  std::vector<double> start_;
  struct PendingColumn {
    double lo, hi, cost;
  };
  std::vector<PendingColumn> new_columns_;
  std::vector<MipModel::Row> new_rows_;
};

}  // namespace tourmap::metro
