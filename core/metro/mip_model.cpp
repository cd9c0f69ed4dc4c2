#include "metro/mip_model.hpp"

#include <coin/Cbc_C_Interface.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>

namespace tourmap::metro {
namespace {

constexpr std::uint32_t kModelMagic = 0x544d4950;   // "TMIP"
constexpr std::uint32_t kResultMagic = 0x544d4952;  // "TMIR"

class Writer {
 public:
  template <typename T>
  void put(T v) {
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <typename T>
  void put_vector(const std::vector<T>& v) {
    put<std::uint64_t>(v.size());
    out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(std::string_view in) : in_(in) {}
  template <typename T>
  T get() {
    if (in_.size() < sizeof(T)) throw std::invalid_argument("truncated MIP data");
    T v;
    std::memcpy(&v, in_.data(), sizeof v);
    in_.remove_prefix(sizeof v);
    return v;
  }
  template <typename T>
  std::vector<T> get_vector() {
    auto n = get<std::uint64_t>();
    if (n > in_.size() / sizeof(T)) throw std::invalid_argument("truncated MIP data");
    std::vector<T> v(n);
    std::memcpy(v.data(), in_.data(), n * sizeof(T));
    in_.remove_prefix(n * sizeof(T));
    return v;
  }

 private:
  std::string_view in_;
};

}  // namespace

int MipModel::add_column(double lo, double hi, double c, bool is_integer, double start_value) {
  lower.push_back(lo);
  upper.push_back(hi);
  cost.push_back(c);
  integer.push_back(is_integer);
  start.push_back(start_value);
  return static_cast<int>(lower.size() - 1);
}

void MipModel::add_row(std::vector<std::pair<int, double>> terms, double lo, double hi) {
  rows.push_back({std::move(terms), lo, hi});
}

std::string serialize(const MipModel& m) {
  Writer w;
  w.put(kModelMagic);
  w.put_vector(m.lower);
  w.put_vector(m.upper);
  w.put_vector(m.cost);
  w.put_vector(m.integer);
  w.put_vector(m.start);
  w.put<std::uint64_t>(m.rows.size());
  for (const auto& r : m.rows) {
    std::vector<int> idx;
    std::vector<double> val;
    for (auto [i, v] : r.terms) {
      idx.push_back(i);
      val.push_back(v);
    }
    w.put_vector(idx);
    w.put_vector(val);
    w.put(r.lo);
    w.put(r.hi);
  }
  return w.take();
}

MipModel deserialize_model(std::string_view bytes) {
  Reader r(bytes);
  if (r.get<std::uint32_t>() != kModelMagic) throw std::invalid_argument("not a MIP model");
  MipModel m;
  m.lower = r.get_vector<double>();
  m.upper = r.get_vector<double>();
  m.cost = r.get_vector<double>();
  m.integer = r.get_vector<std::uint8_t>();
  m.start = r.get_vector<double>();
  std::size_t n = m.lower.size();
  if (m.upper.size() != n || m.cost.size() != n || m.integer.size() != n || (m.start.size() != n && !m.start.empty()))
    throw std::invalid_argument("inconsistent MIP columns");
  auto rows = r.get<std::uint64_t>();
  for (std::uint64_t k = 0; k < rows; ++k) {
    auto idx = r.get_vector<int>();
    auto val = r.get_vector<double>();
    if (idx.size() != val.size()) throw std::invalid_argument("inconsistent MIP row");
    MipModel::Row row;
    for (std::size_t i = 0; i < idx.size(); ++i) {
      if (idx[i] < 0 || static_cast<std::size_t>(idx[i]) >= n) throw std::invalid_argument("MIP row column out of range");
      row.terms.push_back({idx[i], val[i]});
    }
    row.lo = r.get<double>();
    row.hi = r.get<double>();
    m.rows.push_back(std::move(row));
  }
  return m;
}

std::string serialize(const MipResult& res) {
  Writer w;
  w.put(kResultMagic);
  std::vector<char> status(res.status.begin(), res.status.end());
  w.put_vector(status);
  w.put_vector(res.x);
  w.put(res.objective);
  w.put(res.bound);
  w.put(res.gap);
  return w.take();
}

MipResult deserialize_result(std::string_view bytes) {
  Reader r(bytes);
  if (r.get<std::uint32_t>() != kResultMagic) throw std::invalid_argument("not a MIP result");
  MipResult res;
  auto status = r.get_vector<char>();
  res.status.assign(status.begin(), status.end());
  res.x = r.get_vector<double>();
  res.objective = r.get<double>();
  res.bound = r.get<double>();
  res.gap = r.get<double>();
  return res;
}

MipResult solve_with_cbc(const MipModel& m, double time_limit_s, double relative_gap) {
  // One in-process solve at a time: CBC's C interface runs its solver driver, which is not
  // known to be safe from several threads (the server's layout MIPs run in child processes; the
  // small line-order models of concurrent requests run here).
  static std::mutex one_at_a_time;
  const std::lock_guard<std::mutex> lock(one_at_a_time);
  // Column-major matrix for Cbc_loadProblem.
  std::size_t n = m.columns();
  std::vector<std::vector<std::pair<int, double>>> by_col(n);
  for (std::size_t r = 0; r < m.rows.size(); ++r)
    for (auto [c, v] : m.rows[r].terms) by_col[static_cast<std::size_t>(c)].push_back({static_cast<int>(r), v});
  std::vector<CoinBigIndex> starts{0};
  std::vector<int> index;
  std::vector<double> value;
  for (const auto& col : by_col) {
    for (auto [r, v] : col) {
      index.push_back(r);
      value.push_back(v);
    }
    starts.push_back(static_cast<CoinBigIndex>(index.size()));
  }
  std::vector<double> row_lo, row_hi;
  for (const auto& r : m.rows) {
    row_lo.push_back(r.lo);
    row_hi.push_back(r.hi);
  }
  Cbc_Model* model = Cbc_newModel();
  Cbc_setLogLevel(model, 0);
  Cbc_loadProblem(model, static_cast<int>(n), static_cast<int>(m.rows.size()), starts.data(), index.data(), value.data(),
                  m.lower.data(), m.upper.data(), m.cost.data(), row_lo.data(), row_hi.data());
  for (std::size_t c = 0; c < n; ++c)
    if (m.integer[c]) Cbc_setInteger(model, static_cast<int>(c));
  Cbc_setMaximumSeconds(model, time_limit_s);
  // No CglPreProcess: when the time limit runs out during it (a short budget, a slow machine),
  // Debian's Cbc 2.10 dereferences a null pointer in CglPreProcess::postProcess (a SEGV in the
  // solver child; reproduced by the 50 ms improvement test under ASan). Our models are small
  // (Freiburg: 504 columns, 1,182 rows) and start from the fast layout's solution.
  Cbc_setParameter(model, "preprocess", "off");
  Cbc_setAllowableFractionGap(model, relative_gap);
  if (m.start.size() == n) {
    std::vector<int> cols(n);
    for (std::size_t c = 0; c < n; ++c) cols[c] = static_cast<int>(c);
    Cbc_setMIPStartI(model, static_cast<int>(n), cols.data(), m.start.data());
  }
  Cbc_solve(model);
  MipResult res;
  bool has_solution = Cbc_numberSavedSolutions(model) > 0 || Cbc_isProvenOptimal(model);
  if (Cbc_isProvenOptimal(model)) res.status = "optimal";
  else if (Cbc_isProvenInfeasible(model)) res.status = "infeasible";
  else if (Cbc_isSecondsLimitReached(model)) res.status = "time_limit";
  else if (Cbc_secondaryStatus(model) == 2) res.status = "gap";
  else res.status = has_solution ? "stopped" : "no_solution";
  if (has_solution) {
    const double* x = Cbc_getColSolution(model);
    res.x.assign(x, x + n);
    res.objective = Cbc_getObjValue(model);
    res.bound = Cbc_getBestPossibleObjValue(model);
    res.gap = std::abs(res.objective) > 1e-12 ? std::max(0.0, (res.objective - res.bound) / std::abs(res.objective)) : 0.0;
  }
  Cbc_deleteModel(model);
  return res;
}

double max_violation(const MipModel& m, const std::vector<double>& x) {
  double worst = 0;
  for (std::size_t c = 0; c < m.columns(); ++c) {
    worst = std::max({worst, m.lower[c] - x[c], x[c] - m.upper[c]});
    if (m.integer[c]) worst = std::max(worst, std::abs(x[c] - std::round(x[c])));
  }
  for (const auto& r : m.rows) {
    double s = 0;
    for (auto [c, v] : r.terms) s += v * x[static_cast<std::size_t>(c)];
    worst = std::max({worst, r.lo - s, s - r.hi});
  }
  return worst;
}

}  // namespace tourmap::metro
