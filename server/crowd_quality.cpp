#include "crowd_quality.hpp"

#include <algorithm>
#include <cmath>

namespace tourmap::server {

FrameQuality frame_quality(int level, int width, int height, float poe, int jpeg_quality) {
  level = std::clamp(level, 0, QualityController::kLevels - 1);
  const QualityLevel& q = kQualityLevels[static_cast<std::size_t>(level)];
  FrameQuality f;
  f.level = level;
  f.width = level == 0 ? width : std::max(16, static_cast<int>(std::lround(width * q.scale)));
  f.height = level == 0 ? height : std::max(16, static_cast<int>(std::lround(height * q.scale)));
  // A cluster's projected size shrinks with the rendered size: PoE p client pixels is
  // p * (rendered / requested height) rendered pixels.
  f.cut_poe = poe * q.poe_factor * static_cast<float>(f.height) / static_cast<float>(height);
  f.jpeg_quality = std::min(jpeg_quality, q.max_jpeg_quality);
  return f;
}

void QualityController::record(int frame_level, double ms) {
  if (frame_level < 0 || frame_level >= kLevels || !(ms >= 0) || !std::isfinite(ms)) return;
  double& c = cost_ms[static_cast<std::size_t>(frame_level)];
  c = c == 0 ? ms : 0.6 * c + 0.4 * ms;
}

double QualityController::predicted_ms(int at) const {
  at = std::clamp(at, 0, kLevels - 1);
  const auto cost = [this](int l) { return cost_ms[static_cast<std::size_t>(l)]; };
  if (cost(at) > 0) return cost(at);
  int finer = at - 1, coarser = at + 1;
  while (finer >= 0 && cost(finer) <= 0) --finer;
  while (coarser < kLevels && cost(coarser) <= 0) ++coarser;
  const bool has_finer = finer >= 0, has_coarser = coarser < kLevels;
  if (has_finer && has_coarser) {
    const double t = static_cast<double>(at - finer) / (coarser - finer);
    return cost(finer) * std::pow(cost(coarser) / cost(finer), t);
  }
  if (has_finer) return cost(finer) / std::pow(kAssumedStepRatio, at - finer);
  if (has_coarser) return cost(coarser) * std::pow(kAssumedStepRatio, coarser - at);
  return 0;  // nothing measured: try the finest
}

int QualityController::choose(double budget_ms) {
  while (level < kLevels - 1 && predicted_ms(level) > budget_ms) ++level;
  if (level > 0 && predicted_ms(level - 1) <= kFinerHeadroom * budget_ms) --level;
  return level;
}

double frame_budget_ms(int target_fps, std::size_t active_streams) {
  if (target_fps <= 0) return 0;
  return 0.9 * 1000.0 / target_fps / static_cast<double>(std::max<std::size_t>(1, active_streams));
}

}  // namespace tourmap::server
