#include "metro/lp_solve.hpp"

#include <coin/ClpSimplex.hpp>
#include <coin/CoinPackedMatrix.hpp>

#include <vector>

namespace tourmap::metro {

MipResult solve_lp_with_clp(const MipModel& m, double time_limit_s) {
  const int n = static_cast<int>(m.columns());
  std::vector<int> rows, cols;
  std::vector<double> values, row_lo, row_hi;
  for (std::size_t r = 0; r < m.rows.size(); ++r) {
    for (auto [c, v] : m.rows[r].terms) {
      rows.push_back(static_cast<int>(r));
      cols.push_back(c);
      values.push_back(v);
    }
    row_lo.push_back(m.rows[r].lo);
    row_hi.push_back(m.rows[r].hi);
  }
  // Column-ordered from triplets (duplicates in a row are summed).
  CoinPackedMatrix matrix(true, rows.data(), cols.data(), values.data(), static_cast<CoinBigIndex>(values.size()));
  matrix.setDimensions(static_cast<int>(m.rows.size()), n);
  ClpSimplex lp;
  lp.setLogLevel(0);
  // MipModel's 1e30 is CBC's infinity; CLP's is COIN_DBL_MAX.
  auto inf = [](std::vector<double> v) {
    for (auto& x : v) x = x >= 1e30 ? COIN_DBL_MAX : x <= -1e30 ? -COIN_DBL_MAX : x;
    return v;
  };
  const auto lower = inf(m.lower), upper = inf(m.upper);
  row_lo = inf(row_lo);
  row_hi = inf(row_hi);
  lp.loadProblem(matrix, lower.data(), upper.data(), m.cost.data(), row_lo.data(), row_hi.data());
  lp.setMaximumSeconds(time_limit_s);
  lp.primal();  // the dual simplex took 3-5 times longer on the spacing programs
  MipResult res;
  if (lp.isProvenOptimal()) res.status = "optimal";
  else if (lp.isProvenPrimalInfeasible()) res.status = "infeasible";
  else if (lp.hitMaximumIterations() || lp.status() == 3) res.status = "time_limit";
  else res.status = "error";
  if (res.status == "optimal") {
    const double* x = lp.getColSolution();
    res.x.assign(x, x + n);
    res.objective = res.bound = lp.getObjValue();
  }
  return res;
}

}  // namespace tourmap::metro
