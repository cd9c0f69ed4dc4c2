#pragma once
// WS /api/v1/crowd/stream: one render thread (it owns the EGL context; GL contexts are bound to
// a thread) serves every stream in turn. Per stream: the latest valid view message wins, at most
// one frame is in flight (the next is rendered after the previous was written), frames are
// rendered only when the view changed or the animation runs, capped at max_fps; a cap on
// concurrent streams refuses more with close 1013. While the camera moves or the crowd animates,
// frames are rendered at the quality that holds the view's target_fps (crowd_quality.hpp); when
// the camera rests, one full-quality frame follows. A frame identical to the last one sent (no
// animation) is not encoded nor sent.

#include "crowd_quality.hpp"
#include "crowd_scene_render.hpp"
#include "server_state.hpp"

#include "api/crowd_assets.hpp"
#include "api/crowd_view.hpp"

#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

namespace tourmap::server {

class CrowdStreamer {
 public:
  CrowdStreamer(api::CrowdAssets& assets, api::CrowdLimits limits);
  ~CrowdStreamer();
  CrowdStreamer(const CrowdStreamer&) = delete;
  CrowdStreamer& operator=(const CrowdStreamer&) = delete;

  WsEndpoint endpoint();
  void start();  // starts the render thread
  void request_stop();  // asks the render thread to finish its frame and end (any thread)
  void stop();          // request_stop() and join

  std::size_t streams() const;
  std::size_t frames_sent() const { return frames_sent_.load(); }
  std::size_t variants_evicted() const { return variants_evicted_.load(); }
  std::size_t frames_unchanged() const { return frames_unchanged_.load(); }

  // The camera counts as resting this long after the last view message that moved it (and after
  // the stream's last frame); then a frame below full quality is followed by a full one (issue
  // 18: within 300 ms of stopping).
  static constexpr auto kCameraSettle = std::chrono::milliseconds(100);

  // Prepared scene variants (scene and character count) kept at once, and their bytes beyond
  // the shared characters; least recently used ones not on screen are evicted beyond these.
  static constexpr std::size_t kMaxSceneVariants = 12;
  static constexpr std::size_t kMaxSceneVariantBytes = 128u << 20;

 private:
  struct Stream;
  void run();
  void render_one(Stream& s, const std::shared_ptr<WsSession>& session);
  PreparedScene& prepare(const api::CrowdView& view, const std::shared_ptr<WsSession>& session);

  api::CrowdAssets& assets_;
  api::CrowdLimits limits_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::map<WsSession*, std::shared_ptr<Stream>> streams_;
  bool stopping_ = false;
  std::thread thread_;
  std::atomic<std::size_t> frames_sent_{0};
  std::atomic<std::size_t> variants_evicted_{0};
  std::atomic<std::size_t> frames_unchanged_{0};
  struct RenderState;
  std::unique_ptr<RenderState> render_;  // touched only by the render thread
};

}  // namespace tourmap::server
