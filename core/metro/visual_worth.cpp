#include "metro/visual_worth.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>

namespace tourmap::metro {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

struct VisualWorth::Index {
  using Point = bg::model::point<double, 2, bg::cs::cartesian>;
  using Box = bg::model::box<Point>;
  using Value = std::pair<Box, std::uint32_t>;
  bgi::rtree<Value, bgi::rstar<16>> tree;
};

VisualWorth::VisualWorth(std::vector<WorthSource> sources, const WorthParams& params)
    : index_(std::make_unique<Index>()) {
  std::vector<Index::Value> boxes;
  for (std::uint32_t i = 0; i < sources.size(); ++i) {
    const auto& s = sources[i];
    double rho = std::min(s.station_km, params.max_proximity_km);
    double h = std::max(params.k_m * (params.w_rank * s.rank01 + params.w_proximity * rho), params.min_bandwidth_m);
    pos_.push_back(s.pos);
    bandwidth_.push_back(h);
    double reach = 4 * h;
    boxes.push_back({Index::Box({s.pos.x - reach, s.pos.y - reach}, {s.pos.x + reach, s.pos.y + reach}), i});
  }
  index_->tree = bgi::rtree<Index::Value, bgi::rstar<16>>(boxes.begin(), boxes.end());  // bulk load
}

VisualWorth::~VisualWorth() = default;
VisualWorth::VisualWorth(VisualWorth&&) noexcept = default;

double VisualWorth::at(XY u) const {
  if (pos_.empty()) return 0.0;
  double sum = 0.0;
  Index::Point p(u.x, u.y);
  for (auto it = index_->tree.qbegin(bgi::intersects(p)); it != index_->tree.qend(); ++it) {
    auto i = it->second;
    double h2 = bandwidth_[i] * bandwidth_[i];
    double dx = u.x - pos_[i].x, dy = u.y - pos_[i].y;
    double d2 = dx * dx + dy * dy;
    if (d2 > 16 * h2) continue;  // outside the circle of reach (the box is its bound)
    // eq. 5.1: 1/h^2 * K, K = exp(-d^2 / 2h^2) / (2 pi h^2)
    sum += std::exp(-d2 / (2 * h2)) / (2 * M_PI * h2 * h2);
  }
  return sum / static_cast<double>(pos_.size());
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
