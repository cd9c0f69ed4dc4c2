#include "metro/lp_solve.hpp"

#include <coin/ClpSimplex.hpp>
#include <coin/CoinPackedMatrix.hpp>

#include <algorithm>
#include <vector>

namespace tourmap::metro {
namespace {

// MipModel's 1e30 is CBC's infinity; CLP's is COIN_DBL_MAX.
double clp_bound(double x) { return x >= 1e30 ? COIN_DBL_MAX : x <= -1e30 ? -COIN_DBL_MAX : x; }

std::vector<double> clp_bounds(std::vector<double> v) {
  for (auto& x : v) x = clp_bound(x);
  return v;
}

void load(ClpSimplex& lp, const MipModel& m) {
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
  lp.setLogLevel(0);
  const auto lower = clp_bounds(m.lower), upper = clp_bounds(m.upper);
  row_lo = clp_bounds(row_lo);
  row_hi = clp_bounds(row_hi);
  lp.loadProblem(matrix, lower.data(), upper.data(), m.cost.data(), row_lo.data(), row_hi.data());
}

MipResult result_of(const ClpSimplex& lp) {
  MipResult res;
  if (lp.isProvenOptimal()) res.status = "optimal";
  else if (lp.isProvenPrimalInfeasible()) res.status = "infeasible";
  else if (lp.hitMaximumIterations() || lp.status() == 3) res.status = "time_limit";
  else res.status = "error";
  if (res.status == "optimal") {
    const double* x = lp.getColSolution();
    res.x.assign(x, x + lp.getNumCols());
    res.objective = res.bound = lp.getObjValue();
  }
  return res;
}

// Primal simplex (the dual took 3-5 times longer on the spacing programs), from `start` when
// there is one (a values pass).
void solve_primal(ClpSimplex& lp, const std::vector<double>& start, double time_limit_s) {
  lp.setMaximumSeconds(time_limit_s);
  if (start.size() == static_cast<std::size_t>(lp.getNumCols())) {
    lp.setColSolution(start.data());
    lp.primal(1);
  } else {
    lp.primal();
  }
}

}  // namespace

MipResult solve_lp_with_clp(const MipModel& m, double time_limit_s) {
  ClpSimplex lp;
  load(lp, m);
  solve_primal(lp, m.start, time_limit_s);
  return result_of(lp);
}

LpSession::LpSession(const MipModel& m) : lp_(std::make_unique<ClpSimplex>()), start_(m.start) { load(*lp_, m); }

LpSession::~LpSession() = default;

MipResult LpSession::solve(double time_limit_s) {
  flush();
  solve_primal(*lp_, start_, time_limit_s);
  return result_of(*lp_);
}

int LpSession::add_column(double lo, double hi, double cost) {
  new_columns_.push_back({lo, hi, cost});
  return static_cast<int>(columns() - 1);
}

// Terms on one column are summed (CLP's row appends keep duplicates).
void LpSession::add_row(const std::vector<std::pair<int, double>>& terms, double lo, double hi) {
  auto merged = terms;
  std::sort(merged.begin(), merged.end());
  std::size_t k = 0;
  for (std::size_t i = 0; i < merged.size(); ++i) {
    if (k > 0 && merged[k - 1].first == merged[i].first) merged[k - 1].second += merged[i].second;
    else merged[k++] = merged[i];
  }
  merged.resize(k);
  new_rows_.push_back({std::move(merged), lo, hi});
}

std::size_t LpSession::columns() const { return static_cast<std::size_t>(lp_->getNumCols()) + new_columns_.size(); }

std::size_t LpSession::rows() const { return static_cast<std::size_t>(lp_->getNumRows()) + new_rows_.size(); }

// Columns first: the new rows may use them. A new column starts at its lower bound, a new
// row's slack in the basis: the last basis stays a basis.
void LpSession::flush() {
  if (!new_columns_.empty()) {
    std::vector<double> lo, hi, cost;
    std::vector<CoinBigIndex> starts(new_columns_.size() + 1, 0);
    for (const auto& c : new_columns_) {
      lo.push_back(clp_bound(c.lo));
      hi.push_back(clp_bound(c.hi));
      cost.push_back(c.cost);
    }
    lp_->addColumns(static_cast<int>(new_columns_.size()), lo.data(), hi.data(), cost.data(), starts.data(), nullptr,
                    nullptr);
    new_columns_.clear();
  }
  if (!new_rows_.empty()) {
    std::vector<double> lo, hi, values;
    std::vector<int> cols;
    std::vector<CoinBigIndex> starts{0};
    for (const auto& r : new_rows_) {
      lo.push_back(clp_bound(r.lo));
      hi.push_back(clp_bound(r.hi));
      for (auto [c, v] : r.terms) {
        cols.push_back(c);
        values.push_back(v);
      }
      starts.push_back(static_cast<CoinBigIndex>(values.size()));
    }
    lp_->addRows(static_cast<int>(new_rows_.size()), lo.data(), hi.data(), starts.data(), cols.data(), values.data());
    new_rows_.clear();
  }
}

MipResult LpSession::resolve(double time_limit_s) {
  flush();
  lp_->setMaximumSeconds(time_limit_s);
  lp_->dual();
  return result_of(*lp_);
}

}  // namespace tourmap::metro
