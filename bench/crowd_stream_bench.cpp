// Crowd streaming benchmark (issues 5 and 18): the real server (`tourmap serve`, started here on
// a free port with a temporary database) and 1 and 4 WebSocket clients that acknowledge frames as
// the web client does. Per scene, client count and target frame rate (0: every frame at full
// quality, the behaviour before issue 18, measured in the same run as the baseline):
//
//  - moving: the crowd animates and each client orbits its camera (30 degrees a second), sending
//    the next camera as soon as a frame arrives: frames per second per client, end-to-end frame
//    latency (receive time minus the header's timestamp, taken when the server started the
//    frame), the server's LOD cut / render / readback / encode ms, the level and scale of the
//    frames, bytes per frame;
//  - still: animation off; each client orbits for 1.5 s and stops, then waits for the frame that
//    shows its last camera at full quality (the "still" frame): ms from its last camera message
//    to that frame's arrival, over 5 stops per client. "client says": the view messages carry
//    "interacting" (true while orbiting, false with the last camera), as the web client's do;
//    "server guesses": no hint, the server waits for the camera to rest (100 ms).
//
//   build/bench/crowd_stream_bench [--scenes office] [--seconds 10] [--width 1280] [--height 720]
//       [--poe 0.5] [--quality 75] [--target-fps 15] [--stops 5] [--max-subdivision -1] [--db FILE]
//       [--bin build/tourmap] [--data-dir DIR]
// The defaults are the web client's (PoE 0.5, JPEG 75, 15 fps). --db reuses a database (its
// cached hierarchies) across runs; the first run builds them.

#include "http_client.hpp"
#include "server_process.hpp"
#include "temp_dir.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

struct Options {
  std::vector<std::string> scenes = {"office"};
  std::string bin = TOURMAP_BIN, data_dir = TOURMAP_DEFAULT_DATA_DIR, db;
  double seconds = 10, poe = 0.5;
  int width = 1280, height = 720, quality = 75, target_fps = 15, stops = 5, max_subdivision = -1;
};

struct Run {
  std::string scene;
  int target_fps = 0;
  bool moving = true;
  bool hint = true;  // still runs: the client says when it interacts ("interacting"), as the web client does
};

struct ClientResult {
  int frames = 0;
  double seconds = 0, bytes = 0;
  std::vector<double> latency_ms, cut_ms, render_ms, readback_ms, encode_ms, level, scale, still_ms;
  std::string error;
};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

double now_epoch_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch()).count();
}

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The orbit around the scene's default target, `degrees` round from the default eye.
json camera_at(const json& ready, double degrees) {
  const auto& c = ready["default_camera"];
  const double tx = c["target"][0], ty = c["target"][1], tz = c["target"][2];
  const double dx = c["eye"][0].get<double>() - tx, dz = c["eye"][2].get<double>() - tz;
  const double a = degrees * 3.14159265358979 / 180;
  return {{"eye", {tx + std::cos(a) * dx - std::sin(a) * dz, c["eye"][1], tz + std::sin(a) * dx + std::cos(a) * dz}},
          {"target", {tx, ty, tz}},
          {"fov", c["fov"]}};
}

class StreamClient {
 public:
  StreamClient(unsigned short port, const Options& o, const Run& run) : ws_(port, "/api/v1/crowd/stream") {
    ws_.send(json{{"type", "view"}, {"scene", run.scene}, {"mode", "vdr+oc"}, {"poe", o.poe}, {"width", o.width},
                  {"height", o.height}, {"quality", o.quality}, {"animate", run.moving}, {"target_fps", run.target_fps}}
                 .dump());
    ++views_sent_;
    while (!has_frame_) receive();  // the first frame (the scene may need preparing)
  }

  // `interacting`: -1 leaves it out, else the hint the web client sends (true while dragging).
  void look(double degrees, int interacting = -1) {
    json view{{"type", "view"}, {"camera", camera_at(ready_, degrees)}};
    if (interacting >= 0) view["interacting"] = interacting == 1;
    ws_.send(view.dump());
    ++views_sent_;
    last_send_ = Clock::now();
  }

  // Next frame with its stats; acknowledged at once.
  const json& receive() {
    for (;;) {
      auto m = ws_.receive_message(std::chrono::minutes(5));
      if (m.binary) {
        std::uint32_t id = 0;
        std::memcpy(&id, m.data.data() + 4, 4);
        std::memcpy(&sent_ms_, m.data.data() + 8, 8);
        ws_.send(json{{"type", "ack"}, {"frame", id}}.dump());
        received_ms_ = now_epoch_ms();
        received_at_ = Clock::now();
        bytes_ = static_cast<double>(m.data.size() - 24);
        new_picture_ = true;
        continue;
      }
      json j = json::parse(m.data);
      if (j["type"] == "error") throw std::runtime_error(m.data);
      if (j["type"] == "ready") ready_ = j;
      if (j["type"] == "stats") {
        stats_ = std::move(j);
        has_frame_ = true;
        return stats_;
      }
    }
  }

  // Counts a frame (stats of an unchanged picture, sent without one, are not frames).
  void count(ClientResult& r) {
    if (!new_picture_) return;
    new_picture_ = false;
    ++r.frames;
    r.latency_ms.push_back(received_ms_ - sent_ms_);
    r.bytes += bytes_;
    r.cut_ms.push_back(stats_["ms"]["lod_cut"]);
    r.render_ms.push_back(stats_["ms"]["render"]);
    r.readback_ms.push_back(stats_["ms"]["readback"]);
    r.encode_ms.push_back(stats_["ms"]["encode"]);
    r.level.push_back(stats_["quality"]["level"]);
    r.scale.push_back(stats_["quality"]["scale"]);
  }

  // The frame shows the last camera sent, at full quality.
  bool final_frame() const { return stats_["view"].get<std::uint64_t>() >= views_sent_ && stats_["quality"]["level"] == 0; }
  double ms_since_last_send() const {
    return std::chrono::duration<double, std::milli>(received_at_ - last_send_).count();
  }

 private:
  tourmap::test::WsClient ws_;
  json ready_, stats_;
  bool has_frame_ = false, new_picture_ = false;
  std::uint64_t views_sent_ = 0;
  double sent_ms_ = 0, received_ms_ = 0, bytes_ = 0;
  Clock::time_point last_send_, received_at_;
};

constexpr double kDegreesPerSecond = 30;

ClientResult moving(unsigned short port, const Options& o, const Run& run, int client) {
  ClientResult r;
  try {
    StreamClient c(port, o, run);
    const auto start = Clock::now();
    const double offset = 90.0 * client;  // clients look from different sides
    c.look(offset);
    while (seconds_since(start) < o.seconds) {
      c.receive();
      c.count(r);
      c.look(offset + kDegreesPerSecond * seconds_since(start));
    }
    r.seconds = seconds_since(start);
  } catch (const std::exception& e) {
    r.error = "client " + std::to_string(client) + ": " + e.what();
  }
  return r;
}

ClientResult stopping(unsigned short port, const Options& o, const Run& run, int client) {
  ClientResult r;
  try {
    StreamClient c(port, o, run);
    const auto start = Clock::now();
    double degrees = 90.0 * client;
    for (int stop = 0; stop < o.stops; ++stop) {
      const auto orbit = Clock::now();
      degrees += kDegreesPerSecond * 0.05;  // the same camera again would change nothing: no frame
      c.look(degrees, run.hint ? 1 : -1);
      for (;;) {
        c.receive();
        c.count(r);
        degrees += kDegreesPerSecond * 0.05;
        if (seconds_since(orbit) >= 1.5) break;
        c.look(degrees, run.hint ? 1 : -1);
      }
      c.look(degrees, run.hint ? 0 : -1);  // the last move (with the hint: and the user lets go)
      // Stopped: frames until the one that shows the last camera at full quality.
      while (!c.final_frame()) {
        c.receive();
        c.count(r);
      }
      r.still_ms.push_back(c.ms_since_last_send());
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
    }
    r.seconds = seconds_since(start);
  } catch (const std::exception& e) {
    r.error = "client " + std::to_string(client) + ": " + e.what();
  }
  return r;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--scenes" || k == "--scene") o.scenes = split(v);
    else if (k == "--seconds") o.seconds = std::stod(v);
    else if (k == "--width") o.width = std::stoi(v);
    else if (k == "--height") o.height = std::stoi(v);
    else if (k == "--poe") o.poe = std::stod(v);
    else if (k == "--quality") o.quality = std::stoi(v);
    else if (k == "--target-fps") o.target_fps = std::stoi(v);
    else if (k == "--stops") o.stops = std::stoi(v);
    else if (k == "--max-subdivision") o.max_subdivision = std::stoi(v);
    else if (k == "--db") o.db = v;
    else if (k == "--bin") o.bin = v;
    else if (k == "--data-dir") o.data_dir = v;
    else {
      std::fprintf(stderr, "unknown option %s\n", k.c_str());
      return 2;
    }
  }
  tourmap::test::TempDir dir;
  const std::string db = o.db.empty() ? dir.file("bench.db") : o.db;
  tourmap::test::ServerProcess server(o.bin, db,
                                      {"--data-dir", o.data_dir, "--access-log", "off", "--crowd-max-subdivision",
                                       std::to_string(o.max_subdivision), "--crowd-streams", "8"});
  std::printf("crowd stream: %dx%d, PoE %.2f, JPEG %d, vdr+oc; moving: animation on, %.0f s per run; still: "
              "animation off, %d stops per client; target fps 0 = every frame at full quality (before issue 18)\n\n",
              o.width, o.height, o.poe, o.quality, o.seconds, o.stops);
  std::printf("| scene | clients | run | target fps | fps per client | latency p50 | latency p99 | level p50 | scale p50 "
              "| cut ms p50 | render ms p50 | readback ms p50 | encode ms p50 | KiB/frame | still frame ms p50 | still frame ms max |\n");
  std::printf("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& scene : o.scenes) {
    {  // warm-up: prepares the scene (loads or builds the hierarchies) outside the measurement
      StreamClient warm(server.port(), o, {scene, 0, true});
    }
    const std::vector<Run> runs = {{scene, 0, true, true},           {scene, o.target_fps, true, true},
                                   {scene, 0, false, true},          {scene, o.target_fps, false, true},
                                   {scene, o.target_fps, false, false}};
    for (const Run& run : runs)
      for (int clients : {1, 4}) {
          const bool is_moving = run.moving;
          const int target = run.target_fps;
          std::vector<ClientResult> results(static_cast<std::size_t>(clients));
          std::vector<std::thread> threads;
          for (int c = 0; c < clients; ++c)
            threads.emplace_back([&, c] {
              results[static_cast<std::size_t>(c)] =
                  is_moving ? moving(server.port(), o, run, c) : stopping(server.port(), o, run, c);
            });
          for (auto& t : threads) t.join();
          ClientResult all;
          double fps_sum = 0;
          for (const auto& r : results) {
            if (!r.error.empty()) std::fprintf(stderr, "%s\n", r.error.c_str());
            if (r.seconds > 0) fps_sum += r.frames / r.seconds;
            all.frames += r.frames;
            all.bytes += r.bytes;
            for (auto [to, from] : {std::pair{&all.latency_ms, &r.latency_ms}, {&all.cut_ms, &r.cut_ms},
                                    {&all.render_ms, &r.render_ms}, {&all.readback_ms, &r.readback_ms},
                                    {&all.encode_ms, &r.encode_ms}, {&all.level, &r.level}, {&all.scale, &r.scale},
                                    {&all.still_ms, &r.still_ms}})
              to->insert(to->end(), from->begin(), from->end());
          }
          const auto still = [&](double q) {
            return all.still_ms.empty() ? std::string("-") : std::to_string(static_cast<int>(std::lround(percentile(all.still_ms, q))));
          };
          std::printf("| %s | %d | %s | %d | %.2f | %.0f ms | %.0f ms | %.0f | %.2f | %.2f | %.1f | %.2f | %.2f | %.1f | %s | %s |\n",
                      scene.c_str(), clients, is_moving ? "moving" : run.hint ? "still, client says" : "still, server guesses",
                      target, fps_sum / clients,
                      percentile(all.latency_ms, 0.5), percentile(all.latency_ms, 0.99), percentile(all.level, 0.5),
                      percentile(all.scale, 0.5), percentile(all.cut_ms, 0.5), percentile(all.render_ms, 0.5),
                      percentile(all.readback_ms, 0.5), percentile(all.encode_ms, 0.5),
                      all.frames ? all.bytes / all.frames / 1024.0 : 0.0, still(0.5).c_str(), still(1.0).c_str());
          std::fflush(stdout);
        }
  }
  return 0;
}
