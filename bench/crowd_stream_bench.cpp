// Crowd streaming benchmark (issue 5): the real server (`tourmap serve`, started here on a free
// port with a temporary database) and 1 and 4 WebSocket clients that stream a scene with the
// animation running. Per configuration: frames per second per client and in total, end-to-end
// frame latency (client receive time minus the frame header's timestamp, taken when the server
// started rendering the frame: render + encode + send + receive), server encode/render ms from
// the stats, JPEG bytes per frame. Clients acknowledge frames as the web client does.
//
//   build/bench/crowd_stream_bench [--scene office] [--seconds 20] [--width 640] [--height 360]
//       [--poe 2] [--max-subdivision -1] [--db FILE] [--bin build/tourmap] [--data-dir DIR]
// --db reuses a database (its cached hierarchies) across runs; the first run builds them.

#include "http_client.hpp"
#include "server_process.hpp"
#include "temp_dir.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

struct Options {
  std::string scene = "office", bin = TOURMAP_BIN, data_dir = TOURMAP_DEFAULT_DATA_DIR, db;
  double seconds = 20;
  int width = 640, height = 360, max_subdivision = -1;
  double poe = 2;
};

struct ClientResult {
  int frames = 0;
  double seconds = 0;
  std::vector<double> latency_ms, encode_ms, render_ms;
  double bytes = 0;
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

// Streams until the first frame (the scene may need preparing), then counts for `seconds`.
ClientResult stream(unsigned short port, const Options& o, int client) {
  ClientResult r;
  try {
    tourmap::test::WsClient ws(port, "/api/v1/crowd/stream");
    json view = {{"type", "view"}, {"scene", o.scene}, {"mode", "vdr+oc"}, {"poe", o.poe}, {"width", o.width},
                 {"height", o.height}, {"quality", 75}, {"animate", true}};
    ws.send(view.dump());
    bool counting = false;
    Clock::time_point start;
    for (;;) {
      auto m = ws.receive_message(std::chrono::minutes(30));
      if (m.binary) {
        double sent = 0;
        std::memcpy(&sent, m.data.data() + 8, 8);
        std::uint32_t id = 0;
        std::memcpy(&id, m.data.data() + 4, 4);
        ws.send(json{{"type", "ack"}, {"frame", id}}.dump());
        if (counting) {
          ++r.frames;
          r.latency_ms.push_back(now_epoch_ms() - sent);
          r.bytes += static_cast<double>(m.data.size() - 24);
        } else {
          counting = true;  // the first frame starts the clock
          start = Clock::now();
        }
      } else {
        auto j = json::parse(m.data);
        if (j["type"] == "error") throw std::runtime_error(m.data);
        if (j["type"] == "stats" && counting && r.frames > 0) {
          r.encode_ms.push_back(j["ms"]["encode"].get<double>());
          r.render_ms.push_back(j["ms"]["render"].get<double>());
        }
      }
      if (counting && std::chrono::duration<double>(Clock::now() - start).count() >= o.seconds) break;
    }
    r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  } catch (const std::exception& e) {
    r.error = "client " + std::to_string(client) + ": " + e.what();
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--scene") o.scene = v;
    else if (k == "--seconds") o.seconds = std::stod(v);
    else if (k == "--width") o.width = std::stoi(v);
    else if (k == "--height") o.height = std::stoi(v);
    else if (k == "--poe") o.poe = std::stod(v);
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
  std::printf("crowd stream: scene %s, %dx%d, PoE %.2f, vdr+oc, animation on, %.0f s per run\n\n", o.scene.c_str(),
              o.width, o.height, o.poe, o.seconds);
  // Warm-up: prepares the scene (loads or builds the hierarchies) outside the measurement.
  {
    Options warm = o;
    warm.seconds = 1;
    auto r = stream(server.port(), warm, 0);
    if (!r.error.empty()) {
      std::fprintf(stderr, "%s\n", r.error.c_str());
      return 1;
    }
  }
  std::printf("| clients | fps per client | fps total | latency p50 | latency p99 | encode ms p50 | render ms p50 | KiB/frame |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int clients : {1, 4}) {
    std::vector<ClientResult> results(static_cast<std::size_t>(clients));
    std::vector<std::thread> threads;
    for (int c = 0; c < clients; ++c)
      threads.emplace_back([&, c] { results[static_cast<std::size_t>(c)] = stream(server.port(), o, c); });
    for (auto& t : threads) t.join();
    double fps_sum = 0, bytes = 0;
    int frames = 0;
    std::vector<double> lat, enc, ren;
    for (const auto& r : results) {
      if (!r.error.empty()) std::fprintf(stderr, "%s\n", r.error.c_str());
      if (r.seconds > 0) fps_sum += r.frames / r.seconds;
      frames += r.frames;
      bytes += r.bytes;
      lat.insert(lat.end(), r.latency_ms.begin(), r.latency_ms.end());
      enc.insert(enc.end(), r.encode_ms.begin(), r.encode_ms.end());
      ren.insert(ren.end(), r.render_ms.begin(), r.render_ms.end());
    }
    std::printf("| %d | %.2f | %.2f | %.1f ms | %.1f ms | %.2f | %.1f | %.1f |\n", clients, fps_sum / clients, fps_sum,
                percentile(lat, 0.5), percentile(lat, 0.99), percentile(enc, 0.5), percentile(ren, 0.5),
                frames ? bytes / frames / 1024.0 : 0.0);
  }
  return 0;
}
