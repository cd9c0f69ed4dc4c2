#include "crowd_stream.hpp"

#include "crowd_scene_render.hpp"
#include "ws_session.hpp"

#include "render/camera.hpp"
#include "render/crowd_renderer.hpp"
#include "render/egl_context.hpp"
#include "render/jpeg_encoder.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>

namespace tourmap::server {

namespace websocket = boost::beast::websocket;
using Clock = std::chrono::steady_clock;

struct CrowdStreamer::Stream {
  std::weak_ptr<WsSession> session;
  std::uint64_t serial = 0;  // occlusion coherence belongs to one stream's camera
  api::CrowdView view;
  bool has_view = false;   // a valid view arrived
  bool dirty = false;      // the view changed since the last frame
  bool failed = false;     // preparing/rendering failed; wait for a new view
  std::atomic<std::uint32_t> frame_id{0};
  // Flow control: a client that acknowledges frames ({"type":"ack","frame":N}) gets the next
  // frame only after acknowledging the last one, so frames never wait in socket buffers.
  bool uses_acks = false;
  std::uint32_t acked = 0;
  int acks_in_window = 0;
  std::string ready_for;   // the scene key the last "ready" message described
  double anim_t = 0;       // animation clock (s), runs while view.animate
  Clock::time_point last_frame{};
  Clock::time_point window_start = Clock::now();
  int messages_in_window = 0;
  double fps = 0;          // exponential average of the frame rate
  QualityController quality;           // interactive frames' level
  Clock::time_point camera_moved_at{}; // the last view message that moved the camera
  bool camera_dirty = false;           // the camera moved since the last frame started
  Clock::time_point frame_done{};      // when the last frame was sent (or found unchanged)
  bool still_pending = false;          // the last frame sent was below full quality
  // The last frame sent while not animating (at most max_width x max_height x 4 bytes), to
  // skip sending the same picture again.
  std::vector<std::uint8_t> last_rgba;
  int last_width = 0, last_height = 0;
  std::uint64_t views = 0;             // view messages applied; a frame's stats name the count
};

struct CrowdStreamer::RenderState {
  std::unique_ptr<render::EglContext> context;
  std::unique_ptr<render::CrowdRenderer> renderer;
  render::JpegEncoder encoder;
  std::map<std::string, int> model_ids;            // by character key
  // Prepared scene variants by "scene/count", least recently used evicted first (never one a
  // stream is showing): each holds its placements and its occluder model on the GPU.
  struct Variant {
    std::unique_ptr<PreparedScene> prepared;
    std::uint64_t last_used = 0;
    std::size_t bytes = 0;
  };
  std::map<std::string, Variant> scenes;
  std::uint64_t uses = 0;
  std::size_t scene_bytes = 0;
  std::vector<std::uint8_t> rgba;
  std::vector<crowd::Placement> placements;
  std::uint64_t last_stream = 0;  // serial of the stream the renderer's PVS belongs to
};

namespace {

// started_ms: when rendering of the frame started (ms since the Unix epoch), so a client's
// receive time minus it is the whole frame latency: render, encode, send.
std::string frame_header(std::uint32_t id, int width, int height, double started_ms) {
  std::string h(24, '\0');
  std::memcpy(h.data(), "TMF1", 4);
  std::memcpy(h.data() + 4, &id, 4);  // little-endian hosts (x86-64, arm64)
  std::memcpy(h.data() + 8, &started_ms, 8);
  const auto w = static_cast<std::uint16_t>(width), hh = static_cast<std::uint16_t>(height);
  std::memcpy(h.data() + 16, &w, 2);
  std::memcpy(h.data() + 18, &hh, 2);
  h[20] = 1;  // JPEG
  return h;
}

render::RenderMode to_render_mode(api::CrowdMode m) {
  switch (m) {
    case api::CrowdMode::no_lod: return render::RenderMode::no_lod;
    case api::CrowdMode::vdr: return render::RenderMode::vdr;
    case api::CrowdMode::vdr_oc: return render::RenderMode::vdr_oc;
  }
  return render::RenderMode::vdr;
}

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

CrowdStreamer::CrowdStreamer(api::CrowdAssets& assets, api::CrowdLimits limits)
    : assets_(assets), limits_(limits), render_(std::make_unique<RenderState>()) {}

CrowdStreamer::~CrowdStreamer() { stop(); }

std::size_t CrowdStreamer::streams() const {
  std::lock_guard lock(mutex_);
  return streams_.size();
}

WsEndpoint CrowdStreamer::endpoint() {
  WsEndpoint ep;
  ep.on_open = [this](const std::shared_ptr<WsSession>& s) {
    std::lock_guard lock(mutex_);
    if (streams_.size() >= limits_.max_streams) {
      s->send_text(api::ws_error_message("too_many_streams",
                              "the server streams to " + std::to_string(limits_.max_streams) +
                                  " clients at most; try again later"));
      s->close(websocket::close_code::try_again_later, "too many streams");
      return;
    }
    static std::atomic<std::uint64_t> serials{0};
    auto st = std::make_shared<Stream>();
    st->session = s;
    st->serial = ++serials;
    streams_[s.get()] = st;
  };
  ep.on_text = [this](const std::shared_ptr<WsSession>& s, const std::string& text) {
    const auto msg = nlohmann::json::parse(text, nullptr, false);
    const bool is_ack = msg.is_object() && msg.contains("type") && msg["type"] == "ack";
    std::shared_ptr<Stream> st;
    {
      std::lock_guard lock(mutex_);
      auto it = streams_.find(s.get());
      if (it == streams_.end()) return;
      st = it->second;
      // Flooding: more than max_messages_per_s views (or twice max_fps acks) in one second
      // closes the stream.
      const auto now = Clock::now();
      if (now - st->window_start > std::chrono::seconds(1)) {
        st->window_start = now;
        st->messages_in_window = 0;
        st->acks_in_window = 0;
      }
      const bool flooding = is_ack ? ++st->acks_in_window > 2 * limits_.max_fps
                                   : ++st->messages_in_window > limits_.max_messages_per_s;
      if (flooding) {
        streams_.erase(it);
        s->close(websocket::close_code::policy_error,
                 is_ack ? "more than " + std::to_string(2 * limits_.max_fps) + " acks per second"
                        : "more than " + std::to_string(limits_.max_messages_per_s) + " messages per second");
        return;
      }
    }
    if (msg.is_discarded()) {
      s->send_text(api::ws_error_message("invalid_json", "the message is not valid JSON", "type"));
      return;
    }
    if (is_ack) {
      if (!msg.contains("frame") || !msg["frame"].is_number_unsigned()) {
        s->send_text(api::ws_error_message("invalid_parameter", "frame: an ack needs the frame id it acknowledges", "frame"));
        return;
      }
      {
        std::lock_guard lock(mutex_);
        st->uses_acks = true;
        const auto frame = msg["frame"].get<std::uint64_t>();
        const std::uint32_t sent = st->frame_id.load();
        st->acked = std::max<std::uint32_t>(st->acked, static_cast<std::uint32_t>(std::min<std::uint64_t>(frame, sent)));
      }
      wake_.notify_one();
      return;
    }
    try {
      std::lock_guard lock(mutex_);
      const api::CrowdView next = api::apply_view_message(msg, st->view, limits_);
      if (st->has_view && !st->failed && next == st->view) return;  // nothing new to render
      // A camera moved after the first frame: interactive frames until it rests.
      if (st->has_view && st->frame_id.load() > 0 && next.scene == st->view.scene && !next.same_camera(st->view)) {
        st->camera_moved_at = Clock::now();
        st->camera_dirty = true;
      }
      st->view = next;
      ++st->views;
      st->has_view = true;
      st->dirty = true;
      st->failed = false;
    } catch (const api::ApiError& e) {
      s->send_text(api::ws_error_message(e));
      return;
    }
    wake_.notify_one();
  };
  ep.on_close = [this](const std::shared_ptr<WsSession>& s) {
    std::lock_guard lock(mutex_);
    streams_.erase(s.get());
  };
  return ep;
}

void CrowdStreamer::start() {
  std::lock_guard lock(mutex_);
  if (thread_.joinable()) return;
  stopping_ = false;
  thread_ = std::thread([this] { run(); });
}

void CrowdStreamer::request_stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
}

void CrowdStreamer::stop() {
  request_stop();
  if (thread_.joinable()) thread_.join();
}

void CrowdStreamer::run() {
  const auto min_interval = std::chrono::microseconds(1'000'000 / std::max(1, limits_.max_fps));
  for (;;) {
    std::shared_ptr<Stream> due;
    std::shared_ptr<WsSession> session;
    {
      std::unique_lock lock(mutex_);
      // Sleep until a message arrives when no stream wants frames; otherwise poll every 5 ms
      // (a frame becomes due when its predecessor is written or the fps cap allows).
      const auto wants_frames = [this] {
        for (const auto& [key, st] : streams_)
          if (st->has_view && !st->failed &&
              (st->dirty || st->view.animate || (st->still_pending && st->view.interacting != 1)))
            return true;
        return false;
      };
      if (wants_frames()) wake_.wait_for(lock, std::chrono::milliseconds(5));
      else wake_.wait(lock, [&] { return stopping_ || wants_frames(); });
      if (stopping_) break;
      const auto now = Clock::now();
      // Fairness: of the streams due now, the one that waited longest since its last frame; a
      // full-quality frame for a camera that came to rest goes first (it is what a user waits for).
      bool due_still = false;
      for (auto& [key, st] : streams_) {
        auto s = st->session.lock();
        if (!s || s->is_closed() || !st->has_view || st->failed) continue;
        // At rest: no move for kCameraSettle, and none in as long after the last frame (a client
        // that moves the camera once it sees a frame is not at rest while a slow frame renders).
        const bool still = st->still_pending && !st->view.animate && st->view.interacting != 1 &&
                           now - std::max(st->camera_moved_at, st->frame_done) >= kCameraSettle;
        if (!st->dirty && !st->view.animate && !still) continue;  // nothing changed
        if (s->binary_in_flight() > 0) continue;           // previous frame not written yet
        if (st->uses_acks && st->acked < st->frame_id.load()) continue;  // nor acknowledged
        if (now - st->last_frame < min_interval) continue;  // fps cap
        if (!due || (still && !due_still) || (still == due_still && st->last_frame < due->last_frame)) {
          due = st;
          due_still = still;
          session = std::move(s);
        }
      }
      if (!due) continue;
    }
    render_one(*due, session);
  }
  // GL objects go before the context.
  render_->scenes.clear();
  render_->scene_bytes = 0;
  render_->renderer.reset();
  render_->context.reset();
}

namespace {

std::string variant_key(const api::CrowdView& view) {
  const auto* spec = crowd::find_scene_spec(view.scene);
  return view.scene + "/" + std::to_string(view.count > 0 ? view.count : spec->default_count);
}

// Host and GPU bytes a variant holds beyond the shared characters: its agents and obstacles,
// and the occluder model (about 3 floats and 1 index per vertex, 3 indices per triangle).
std::size_t variant_bytes(const PreparedScene& p) {
  const auto boxes = crowd::boxes_model(p.scene);
  return sizeof(PreparedScene) + p.scene.agents.capacity() * sizeof(p.scene.agents[0]) +
         p.scene.occluders.capacity() * sizeof(p.scene.occluders[0]) +
         boxes.positions.size() * sizeof(boxes.positions[0]) * 2 + boxes.indices.size() * sizeof(std::uint32_t);
}

}  // namespace

PreparedScene& CrowdStreamer::prepare(const api::CrowdView& view, const std::shared_ptr<WsSession>& session) {
  const auto* spec = crowd::find_scene_spec(view.scene);
  const int count = view.count > 0 ? view.count : spec->default_count;
  const std::string key = variant_key(view);
  auto& scenes = render_->scenes;
  if (auto it = scenes.find(key); it != scenes.end()) {
    it->second.last_used = ++render_->uses;
    return *it->second.prepared;
  }
  // Room for one more: evict the least recently used variants no stream is showing. With at
  // most max_streams streams and kMaxSceneVariants above that, there is always one to evict.
  std::set<std::string> showing;
  {
    std::lock_guard lock(mutex_);
    for (const auto& [s, st] : streams_)
      if (st->has_view) showing.insert(variant_key(st->view));
  }
  while (scenes.size() >= kMaxSceneVariants || render_->scene_bytes > kMaxSceneVariantBytes) {
    auto victim = scenes.end();
    for (auto it = scenes.begin(); it != scenes.end(); ++it)
      if (!showing.count(it->first) && (victim == scenes.end() || it->second.last_used < victim->second.last_used))
        victim = it;
    if (victim == scenes.end()) break;  // all shown: the bound is max_streams variants then
    render_->renderer->remove_model(victim->second.prepared->boxes_model);
    render_->scene_bytes -= victim->second.bytes;
    scenes.erase(victim);
    ++variants_evicted_;
  }
  auto progress = [&session, &view](const std::string& stage, const std::string& model, int done, int total) {
    session->send_text(nlohmann::json{{"type", "progress"}, {"scene", view.scene}, {"stage", stage},
                                      {"model", model}, {"done", done}, {"total", total}}
                           .dump());
  };
  // Inserted only once prepared: a failed preparation leaves nothing behind.
  auto prepared = prepare_scene(assets_, *render_->renderer, render_->model_ids, *spec, count, progress);
  const std::size_t bytes = variant_bytes(*prepared);
  render_->scene_bytes += bytes;
  auto& slot = scenes[key];
  slot = {std::move(prepared), ++render_->uses, bytes};
  return *slot.prepared;
}

namespace {

// The lowest eye the renderer is given (metres above the ground plane y = 0).
constexpr float kMinEyeHeightM = 0.05f;

std::string ready_json(const std::string& scene, const PreparedScene& p) {
  const auto& cam = p.scene.default_camera;
  const auto& b = p.scene.bounds;
  return nlohmann::json{{"type", "ready"},
                        {"scene", scene},
                        {"characters", p.scene.count},
                        {"triangles", p.full_triangles},
                        {"default_camera",
                         {{"eye", {cam.eye.x(), cam.eye.y(), cam.eye.z()}},
                          {"target", {cam.target.x(), cam.target.y(), cam.target.z()}},
                          {"fov", cam.fov_deg}}},
                        {"bounds",
                         {{"min", {b.min().x(), b.min().y(), b.min().z()}},
                          {"max", {b.max().x(), b.max().y(), b.max().z()}}}}}
      .dump();
}

}  // namespace

void CrowdStreamer::render_one(Stream& st, const std::shared_ptr<WsSession>& session) {
  api::CrowdView view;
  bool changed = false, in_motion = false;
  std::uint64_t views = 0;
  Clock::time_point previous;
  std::size_t active = 1;
  const auto t0 = Clock::now();
  {
    std::lock_guard lock(mutex_);
    view = st.view;
    views = st.views;
    changed = st.dirty;
    st.dirty = false;
    previous = st.last_frame;
    // A client that says whether it interacts is believed; otherwise a frame for a camera move
    // (however long other streams' frames delayed it) or a recent move counts.
    in_motion = view.animate || view.interacting == 1 ||
                (view.interacting == -1 && (st.camera_dirty || t0 - st.camera_moved_at < kCameraSettle));
    st.camera_dirty = false;
    // Streams that want frames continuously share the render thread, hence each one's budget.
    active = 0;
    for (const auto& [key, other] : streams_)
      if (other->has_view && !other->failed &&
          (other->view.animate || other->dirty || t0 - other->camera_moved_at < std::chrono::milliseconds(500)))
        ++active;
  }
  const double started_ms =
      std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch()).count();
  try {
    if (!render_->context) {
      render_->context = std::make_unique<render::EglContext>();
      render_->renderer = std::make_unique<render::CrowdRenderer>(*render_->context);
    }
    PreparedScene& p = prepare(view, session);
    const std::string scene_key = view.scene + "/" + std::to_string(p.scene.count);
    if (st.ready_for != scene_key) {  // every stream hears "ready" when its scene is ready
      session->send_text(ready_json(view.scene, p));
      st.ready_for = scene_key;
    }
    if (view.animate && previous != Clock::time_point{})
      st.anim_t += std::min(0.25, std::chrono::duration<double>(t0 - previous).count());  // no jumps after stalls

    const auto t_start = Clock::now();  // after preparing: the frame's own cost
    const int level = in_motion && view.target_fps > 0 ? st.quality.choose(frame_budget_ms(view.target_fps, active)) : 0;
    const FrameQuality fq = frame_quality(level, view.width, view.height, view.poe, view.quality);

    const auto& dc = p.scene.default_camera;
    SceneCamera cam;
    cam.eye = view.has_camera ? crowd::Vec3(view.eye[0], view.eye[1], view.eye[2]) : dc.eye;
    cam.target = view.has_camera ? crowd::Vec3(view.target[0], view.target[1], view.target[2]) : dc.target;
    cam.fov_deg = view.has_camera ? view.fov : dc.fov_deg;
    // An eye under the floor would see the underside of the ground plane and nothing else: it is
    // lifted just above the ground box (2 cm). Should that land it on the target, it goes up 1 m.
    cam.eye.y() = std::max(cam.eye.y(), kMinEyeHeightM);
    if ((cam.eye - cam.target).squaredNorm() < 1e-6f) cam.eye.y() += 1.f;
    cam.width = fq.width;
    cam.height = fq.height;
    render::FrameRequest req;
    scene_frame_request(p, st.anim_t, cam, to_render_mode(view.mode), fq.cut_poe, view.heatmap, req,
                        render_->placements);
    if (render_->last_stream != st.serial) render_->renderer->reset_coherence();
    render_->last_stream = st.serial;
    render::FrameStats fs{};
    render_->renderer->render(req, render_->rgba, fs);
    const auto t1 = Clock::now();
    // The same picture as the last one sent (a view message that changed nothing visible, such
    // as VDR+OC to VDR, or a rest after frames at full quality) is not encoded nor sent again;
    // its stats are, naming the frame the client already shows, with "unchanged": true.
    const bool unchanged = !view.animate && st.last_width == fq.width && st.last_height == fq.height &&
                           st.last_rgba == render_->rgba;
    const std::uint32_t id = unchanged ? st.frame_id.load() : ++st.frame_id;
    std::string message;
    if (unchanged) {
      ++frames_unchanged_;
    } else {
      message = frame_header(id, fq.width, fq.height, started_ms);
      render_->encoder.encode_rgba_append(render_->rgba.data(), fq.width, fq.height, fq.jpeg_quality, true, message);
    }
    const auto t2 = Clock::now();
    const std::size_t bytes = unchanged ? 0 : message.size() - 24;
    if (!unchanged) {
      ++frames_sent_;  // before the client can see the frame: /metrics never lags what it got
      session->send_binary(std::move(message));
      if (view.animate) {
        st.last_rgba.clear();
        st.last_width = st.last_height = 0;
      } else {
        st.last_rgba = render_->rgba;
        st.last_width = fq.width;
        st.last_height = fq.height;
      }
    }
    st.quality.record(fq.level, ms_between(t_start, t2));
    const double frame_ms = ms_between(t0, t2);
    if (previous != Clock::time_point{}) {
      const double dt = std::chrono::duration<double>(t0 - previous).count();
      if (dt > 0) st.fps = st.fps == 0 ? 1.0 / dt : 0.8 * st.fps + 0.2 / dt;
    }
    const QualityLevel& ql = kQualityLevels[static_cast<std::size_t>(fq.level)];
    session->send_text(nlohmann::json{{"type", "stats"},
                                      {"frame", id},
                                      {"scene", view.scene},
                                      {"mode", api::mode_name(view.mode)},
                                      {"poe", view.poe},
                                      {"width", fq.width},
                                      {"height", fq.height},
                                      {"quality",
                                       {{"mode", in_motion ? "interactive" : "still"},
                                        {"level", fq.level},
                                        {"scale", fq.level == 0 ? 1.f : ql.scale},
                                        {"poe", view.poe * ql.poe_factor},
                                        {"jpeg", fq.jpeg_quality},
                                        {"target_fps", view.target_fps}}},
                                      {"characters", p.scene.count},
                                      {"full_triangles", p.full_triangles},
                                      {"triangles", fs.triangles},
                                      {"clusters",
                                       {{"drawn", fs.clusters_drawn},
                                        {"frustum_culled", fs.frustum_culled},
                                        {"occluded", fs.occluded}}},
                                      {"occlusion_queries", fs.occlusion_queries},
                                      {"ms",
                                       {{"lod_cut", fs.lod_cut_ms},
                                        {"render", fs.render_ms},
                                        {"readback", fs.readback_ms},
                                        {"encode", ms_between(t1, t2)},
                                        {"frame", frame_ms}}},
                                      {"fps", st.fps},
                                      {"changed", changed},
                                      {"unchanged", unchanged},
                                      {"view", views},
                                      {"bytes", bytes}}
                           .dump());
    std::lock_guard lock(mutex_);
    st.still_pending = fq.level > 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "crowd: stream failed: %s\n", e.what());
    session->send_text(api::ws_error_message("unavailable", std::string("cannot render the scene: ") + e.what()));
    std::lock_guard lock(mutex_);
    st.failed = true;
  }
  std::lock_guard lock(mutex_);
  st.last_frame = t0;
  st.frame_done = Clock::now();
}

}  // namespace tourmap::server
