#include "metro/worth_density.hpp"

#include <cmath>

namespace tourmap::metro::worth {

PointDensity::PointDensity(std::span<const XY> pts, const Bounds& clip) {
  auto inside = [&](XY p) { return p.x >= clip.lo.x && p.x <= clip.hi.x && p.y >= clip.lo.y && p.y <= clip.hi.y; };
  for (const auto& p : pts)
    if (inside(p)) box_.add(p);
  if (!(box_.lo.x <= box_.hi.x)) box_.add(clip.lo.x <= clip.hi.x ? clip.lo : XY{0, 0});  // none inside
  double w = box_.hi.x - box_.lo.x, h = box_.hi.y - box_.lo.y;
  const double side = std::max({w, h, 1.0});
  const int g = std::clamp(static_cast<int>(std::sqrt(pts.size() / 4.0)), 16, 512);
  cell_ = side / g;
  gx_ = std::clamp(static_cast<int>(std::ceil(w / cell_)), 1, g);
  gy_ = std::clamp(static_cast<int>(std::ceil(h / cell_)), 1, g);
  counts_.assign(static_cast<std::size_t>(gx_) * gy_, 0);
  for (const auto& p : pts) {
    if (!inside(p)) continue;
    const int i = static_cast<int>(std::clamp((p.x - box_.lo.x) / cell_, 0.0, gx_ - 1.0));
    const int j = static_cast<int>(std::clamp((p.y - box_.lo.y) / cell_, 0.0, gy_ - 1.0));
    ++counts_[static_cast<std::size_t>(j) * gx_ + i];
  }
  Occupancy base{gx_, gy_, std::vector<std::uint8_t>(counts_.size())};
  for (std::size_t c = 0; c < counts_.size(); ++c) base.used[c] = counts_[c] > 0;
  pyramid_.push_back(std::move(base));
  while (pyramid_.back().gx > 1 || pyramid_.back().gy > 1) {
    const Occupancy& f = pyramid_.back();
    Occupancy up{(f.gx + 1) / 2, (f.gy + 1) / 2, {}};
    up.used.assign(static_cast<std::size_t>(up.gx) * up.gy, 0);
    for (int j = 0; j < f.gy; ++j)
      for (int i = 0; i < f.gx; ++i) up.used[static_cast<std::size_t>(j / 2) * up.gx + i / 2] |= f.used[static_cast<std::size_t>(j) * f.gx + i];
    pyramid_.push_back(std::move(up));
  }
  sat_.assign(static_cast<std::size_t>(gx_ + 1) * (gy_ + 1), 0.0);
  const std::size_t row = gx_ + 1;
  for (int j = 0; j < gy_; ++j)
    for (int i = 0; i < gx_; ++i)
      sat_[(j + 1) * row + i + 1] = counts_[j * gx_ + i] + sat_[j * row + i + 1] + sat_[(j + 1) * row + i] - sat_[j * row + i];
}

}  // namespace tourmap::metro::worth
