#pragma once
// Interactive and still quality for the crowd stream (issue 18), as remote renderers such as
// vtk.js do it: while the camera moves (or the crowd animates), frames are rendered at a lower
// resolution, a coarser LOD cut and a lower JPEG quality, chosen to hold the client's target
// frame rate; once the camera rests, one frame at the full resolution and quality follows.
//
// The controller is plain logic over measured frame costs (no clock, no I/O), so its policy is
// unit-tested with made-up costs.

#include <array>
#include <cstddef>

namespace tourmap::server {

// One rung of the ladder. The PoE (pixels of error, sec. 3.5.1) is given in the client's
// pixels: `poe_factor` multiplies the requested PoE, and the cut is made at the rendered size.
struct QualityLevel {
  float scale;           // of the requested width and height
  float poe_factor;      // requested PoE x this, in the client's pixels
  int max_jpeg_quality;  // the requested JPEG quality, capped at this
};

// Level 0 is the full quality the client asked for. Each further rung costs 1.2-1.6x less on
// llvmpipe (fewer pixels to shade, fewer triangles to skin; views are mostly vertex-bound there),
// measured with bench/crowd_stream_bench on the office scene; the last one is for four clients
// sharing the render thread while the crowd walks.
inline constexpr std::array<QualityLevel, 7> kQualityLevels = {{
    {1.0f, 1.f, 100},
    {0.85f, 1.5f, 80},
    {0.7f, 2.f, 70},
    {0.6f, 3.f, 65},
    {0.5f, 4.f, 60},
    {0.4f, 6.f, 55},
    {0.34f, 10.f, 50},
}};

// What one frame is rendered with.
struct FrameQuality {
  int level = 0;
  int width = 0, height = 0;  // rendered (and sent) size
  float cut_poe = 0;          // PoE for the cut at the rendered size
  int jpeg_quality = 0;
};

// The frame settings for `level` given the client's request (level 0 is the request itself).
// Sizes keep the aspect ratio and stay >= 16 pixels.
FrameQuality frame_quality(int level, int width, int height, float poe, int jpeg_quality);

// Chooses the level of each interactive frame from the measured cost (ms of the render thread:
// cut, render, readback, encode) of the frames rendered before.
struct QualityController {
  static constexpr int kLevels = static_cast<int>(kQualityLevels.size());
  // Cost ratio assumed per level beyond the measured ones. Between two measured levels the cost
  // is interpolated geometrically: on llvmpipe the ratio is 1.2-1.6 per level (vertex-bound
  // views gain less from fewer pixels than fill-bound ones).
  static constexpr double kAssumedStepRatio = 1.4;
  // A finer level is tried only when its predicted cost leaves this much of the budget free, so
  // the choice does not flip between two levels every frame.
  static constexpr double kFinerHeadroom = 0.9;

  int level = 0;
  std::array<double, kQualityLevels.size()> cost_ms{};  // smoothed; 0: not measured yet

  // Records what a frame at `frame_level` cost.
  void record(int frame_level, double ms);
  // The predicted cost of a level: measured, interpolated between the nearest measured finer and
  // coarser levels, or extrapolated from the nearest measured one.
  double predicted_ms(int at) const;
  // Moves `level` to the finest level predicted to fit `budget_ms` (coarser by as many levels
  // as needed, finer by one at a time so each step is measured) and returns it.
  int choose(double budget_ms);
};

// The render thread's time one stream may use per frame to reach `target_fps`, when
// `active_streams` streams want frames continuously (they share the thread), keeping a tenth
// for sending, acknowledging and scheduling.
double frame_budget_ms(int target_fps, std::size_t active_streams);

}  // namespace tourmap::server
