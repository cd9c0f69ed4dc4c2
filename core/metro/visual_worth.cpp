#include "metro/visual_worth.hpp"

#include "metro/worth_approximation.hpp"
#include "metro/worth_density.hpp"

#include "util/stop.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <mutex>
#include <numeric>

namespace tourmap::metro {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

struct VisualWorth::Index {
  using Point = bg::model::point<double, 2, bg::cs::cartesian>;
  using Box = bg::model::box<Point>;
  using Value = std::pair<Box, std::uint32_t>;
  std::once_flag built;
  bgi::rtree<Value, bgi::rstar<16>> tree;
};

VisualWorth::VisualWorth(std::vector<WorthSource> sources, const WorthParams& params)
    : index_(std::make_unique<Index>()) {
  pos_.reserve(sources.size());
  bandwidth_.reserve(sources.size());
  for (const auto& s : sources) {
    double rho = std::min(s.station_km, params.max_proximity_km);
    double h = std::max(params.k_m * (params.w_rank * s.rank01 + params.w_proximity * rho), params.min_bandwidth_m);
    pos_.push_back(s.pos);
    bandwidth_.push_back(h);
  }
  if (std::any_of(sources.begin(), sources.end(), [](const WorthSource& s) { return s.weight != 1.0; }))
    for (const auto& s : sources) weight_.push_back(s.weight);
}

VisualWorth::~VisualWorth() = default;
VisualWorth::VisualWorth(VisualWorth&&) noexcept = default;

const VisualWorth::Index& VisualWorth::index() const {
  std::call_once(index_->built, [this] {
    std::vector<Index::Value> boxes;
    boxes.reserve(pos_.size());
    for (std::uint32_t i = 0; i < pos_.size(); ++i) {
      const auto& p = pos_[i];
      double reach = 4 * bandwidth_[i];
      boxes.push_back({Index::Box({p.x - reach, p.y - reach}, {p.x + reach, p.y + reach}), i});
    }
    index_->tree = bgi::rtree<Index::Value, bgi::rstar<16>>(boxes.begin(), boxes.end());  // bulk load
  });
  return *index_;
}

double VisualWorth::at(XY u) const {
  if (pos_.empty()) return 0.0;
  std::size_t visited = 0;
  return sum_at(u, visited) / static_cast<double>(pos_.size());
}

double VisualWorth::sum_at(XY u, std::size_t& visited) const {
  double sum = 0.0;
  Index::Point p(u.x, u.y);
  const auto& tree = index().tree;
  for (auto it = tree.qbegin(bgi::intersects(p)); it != tree.qend(); ++it) {
    ++visited;
    auto i = it->second;
    double h2 = bandwidth_[i] * bandwidth_[i];
    double dx = u.x - pos_[i].x, dy = u.y - pos_[i].y;
    double d2 = dx * dx + dy * dy;
    if (d2 > 16 * h2) continue;  // outside the circle of reach (the box is its bound)
    // eq. 5.1: 1/h^2 * K, K = exp(-d^2 / 2h^2) / (2 pi h^2); times the interest weight
    const double kernel = std::exp(-d2 / (2 * h2)) / (2 * M_PI * h2 * h2);
    sum += weight_.empty() ? kernel : weight_[i] * kernel;
  }
  return sum;
}


// ---------------------------------------------------------------------------------------------
// Batched evaluation. See the header for the method and its error bound; the approximation is
// in worth_approximation.cpp.

using worth::Bounds;
using worth::kStopEvery;
using worth::PointDensity;

std::vector<double> VisualWorth::at_points(std::span<const XY> points, const WorthEvalOptions& options,
                                           WorthEvalReport* report) const {
  WorthEvalReport local;
  WorthEvalReport& rep = report ? *report : local;
  rep = {};
  std::vector<double> out(points.size(), 0.0);
  if (pos_.empty() || points.empty()) return out;
  util::check_stop();

  // The exact work: per POI, the points within its reach (a 4 h box, times pi/4 for the
  // disc). Points beyond every POI's reach cost nothing and are left out of the table.
  Bounds reach;
  double hmin = std::numeric_limits<double>::infinity(), hmax = 0;
  for (std::size_t i = 0; i < pos_.size(); ++i) {
    reach.add(pos_[i]);
    hmin = std::min(hmin, bandwidth_[i]);
    hmax = std::max(hmax, bandwidth_[i]);
  }
  const bool regular = hmin > 0 && std::isfinite(hmax);  // else only at() knows what to do
  reach.lo = {reach.lo.x - 4 * hmax, reach.lo.y - 4 * hmax};
  reach.hi = {reach.hi.x + 4 * hmax, reach.hi.y + 4 * hmax};
  PointDensity density(points, reach);
  std::vector<double> work(pos_.size());
  for (std::size_t i = 0; i < pos_.size(); ++i) {
    if (i % (32 * kStopEvery) == 0) util::check_stop();
    const double r = 4 * bandwidth_[i];
    work[i] = density.in_box({pos_[i].x - r, pos_[i].y - r}, {pos_[i].x + r, pos_[i].y + r}) * (M_PI / 4);
    rep.estimated_work += work[i];
  }
  const double n = static_cast<double>(pos_.size());

  if (rep.estimated_work <= options.work_budget || !regular) {
    // Exact, through at()'s sum (the same doubles). The estimate assumes points spread evenly
    // within a table cell; should the kernels actually visited pass 3 times the budget (points
    // packed where POIs are), the approximation takes over.
    const double per_point = rep.estimated_work / static_cast<double>(points.size());
    const auto every = static_cast<std::size_t>(std::clamp(1e6 / std::max(per_point, 1.0), 1.0, double(kStopEvery)));
    const double limit = 3 * std::max(options.work_budget, rep.estimated_work) * (4 / M_PI) + 1e6;
    std::size_t visited = 0;
    std::size_t k = 0;
    for (; k < points.size(); ++k) {
      if (k % every == 0) {
        util::check_stop();
        if (double(visited) > limit && regular) break;
      }
      out[k] = sum_at(points[k], visited) / n;
    }
    if (k == points.size()) {
      rep.exact = true;
      rep.exact_sources = pos_.size();
      return out;
    }
    std::fill(out.begin(), out.end(), 0.0);
  }

  const auto approx = worth::approximate_worth(pos_, bandwidth_, weight_, points, density, work, options.grids_only, out);
  rep.exact = false;
  rep.exact_sources = approx.exact_sources;
  rep.levels = approx.levels;
  rep.tiles = approx.tiles;
  // Catmull-Rom weights ring a little below zero where a kernel ends; the field is >= 0.
  for (auto& v : out) v = std::max(0.0, v) / n;
  return out;
}

std::vector<double> VisualWorth::raster(const WorthRaster& grid, const WorthEvalOptions& options,
                                        WorthEvalReport* report) const {
  std::vector<XY> points;
  points.reserve(grid.width * grid.height);
  const double dx = (grid.hi.x - grid.lo.x) / static_cast<double>(grid.width);
  const double dy = (grid.hi.y - grid.lo.y) / static_cast<double>(grid.height);
  for (std::size_t j = 0; j < grid.height; ++j) {
    util::check_stop();
    for (std::size_t i = 0; i < grid.width; ++i)
      points.push_back({grid.lo.x + dx * (i + 0.5), grid.hi.y - dy * (j + 0.5)});
  }
  return at_points(points, options, report);
}

std::vector<double> ranks01_from_scores(const std::vector<double>& scores) {
  std::vector<std::size_t> order(scores.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return scores[a] > scores[b]; });
  std::vector<double> ranks(scores.size());
  for (std::size_t r = 0; r < order.size(); ++r) ranks[order[r]] = static_cast<double>(r + 1) / scores.size();
  return ranks;
}

}  // namespace tourmap::metro
