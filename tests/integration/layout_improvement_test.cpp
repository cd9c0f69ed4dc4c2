// The background improvement of default metro layouts against a real server: the default
// request answers with the fast layout at once, the MIP runs afterwards, a layout_improved
// event on WS /api/v1/events announces it, and the same request then gets the improved layout.
//
// The network is Freiburg's (74 stations, imported by each test): the MIP started from the fast
// layout, with its place term and the acceptance guards (metro/mip_polish.hpp), wins within the
// server's 10 s of CBC CPU (optimal in 4-7 s: 33 -> 32 bends along lines, displacement 0.47 ->
// 0.52 mean edges, the smallest gap kept at 0.53). Earlier networks stopped serving as the fast
// path got better: a hand-made 10-station one (its fast layout has no bend), then Lisbon (the
// MIP's optimum adds a crossing, so it is refused). Should the MIP no longer win on Freiburg,
// the first test says so and another network is needed (Chicago: 20 -> 15 bends in 7-10 s).

#include "live_server.hpp"
#include "slowdown.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <regex>
#include <string>
#include <thread>
#include <vector>

namespace tourmap::test {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

constexpr const char* kCity = "freiburg";
const std::string kLayout = "/api/v1/cities/freiburg/layout";
// How long a background job may take here. About 8 s idle, but the job runs at nice 10 and
// CBC's budget is CPU time (api/mip_runner.hpp): beside other tests on both cores it gets a
// tenth of a core or less, and it still must finish and win.
// Below ctest's 300 s per integration test, so that a job that never wins fails here, with
// the layout's state, rather than by ctest's timeout. Under ASan CBC alone may take most of
// kWinnable's 150 s of CPU.
constexpr std::chrono::seconds kJobWait{240};
// The tests that need Freiburg's MIP to win give CBC more than the server's default 10 s of
// CPU: it stops at the optimum anyway (4-8 s in the Release build), but under ASan, which
// intercepts CBC's allocations in the child process, 10 s were not enough to find it, and 60 s
// not always (a clean-clone CI run: CBC killed at its 60 s + 3 s of CPU, no incumbent kept).
const std::vector<std::string> kWinnable = {"--improve-mip", "150"};

// Imports Freiburg (again: a new city version) into the running server's database.
void import_freiburg(const LiveServer& live) {
  const auto r = run_command({kTourmapBin, "import", "metro", data_file("metro/loom_freiburg.json"), "--format", "loom",
                              "--city", kCity, "--name", "Freiburg", "--attribution", "VAG Freiburg GTFS feed; line graph by LOOM",
                              "--db", live.db(), "--force"});
  if (r.exit_code != 0) throw std::runtime_error("import failed: " + r.output);
}

// A gauge's value from /metrics (-1 when missing).
double gauge(const LiveServer& live, const std::string& name) {
  const auto text = live.get("/metrics").body;
  std::smatch m;
  if (!std::regex_search(text, m, std::regex("\n" + name + " ([0-9.e+-]+)"))) return -1;
  return std::stod(m[1]);
}

// Waits until no improvement is queued or running.
void wait_idle(const LiveServer& live, std::chrono::seconds timeout) {
  const auto until = Clock::now() + timeout;
  while (Clock::now() < until) {
    if (gauge(live, "tourmap_layout_improvements_queued") == 0 &&
        gauge(live, "tourmap_layout_improvements_running") == 0)
      return;
    std::this_thread::sleep_for(50ms);
  }
  FAIL() << "improvements still queued or running after " << timeout.count() << " s";
}

// The next event of `type` (others, such as the import's catalog event, are skipped); null
// when none arrives in time.
nlohmann::json next_event(WsClient& ws, const std::string& type, std::chrono::milliseconds timeout) {
  const auto until = Clock::now() + timeout;
  while (Clock::now() < until) {
    std::string text;
    try {
      text = ws.receive(std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now()) + 1ms);
    } catch (const std::exception&) {
      return nullptr;  // timed out
    }
    auto ev = nlohmann::json::parse(text);
    if (ev.value("type", "") == type) return ev;
  }
  return nullptr;
}

// True when Freiburg's job ended without a win because CBC proved its optimum and that optimum
// had no fewer bends than the job's own fast layout. Under ASan the fast path stops at its time
// budgets and its layout varies (a clean-clone CI run: 32 bends both); only then may a test that
// needs the MIP to win skip. A MIP that was killed, found nothing or never ran still fails.
bool mip_was_no_better(const LiveServer& live) {
  wait_idle(live, kJobWait);
  auto solver = live.get_json(kLayout)["solver"];
  if (solver["improvement"] != "none") return false;
  auto& mip = solver["tried"]["mip"];
  return mip["status"] == "optimal" && mip["accepted"] == false && mip["reason"].is_string() &&
         mip["reason"].get<std::string>().find(" bends, the fast layout ") != std::string::npos;
}

TEST(LayoutImprovement, DefaultLayoutIsFastThenImprovedAndAnnounced) {
  LiveServer live(kWinnable);
  import_freiburg(live);
  WsClient ws(live.port(), "/api/v1/events");
  ASSERT_EQ(nlohmann::json::parse(ws.receive(5s))["type"], "hello");

  const auto started = Clock::now();
  const auto first = live.get(kLayout);
  const double first_s = std::chrono::duration<double>(Clock::now() - started).count();
  ASSERT_EQ(first.status, 200) << first.body;
  const auto fast = nlohmann::json::parse(first.body);
  // Answered before the MIP ran: the fast layout, and the promise of an improvement.
  EXPECT_EQ(fast["solver"]["kind"], "fast") << fast["solver"];
  EXPECT_EQ(fast["solver"]["improvement"], "scheduled") << fast["solver"];
  EXPECT_FALSE(fast["solver"].contains("mip")) << fast["solver"];
  EXPECT_LT(first_s, 2.0);  // tens of milliseconds unless the machine is very busy

  const auto event = next_event(ws, "layout_improved", kJobWait);
  if (event.is_null() && mip_was_no_better(live)) GTEST_SKIP() << "the MIP's optimum was no better than this run's fast layout";
  ASSERT_FALSE(event.is_null()) << "no layout_improved event within " << kJobWait.count() << " s; the layout now: "
                                << nlohmann::json::parse(live.get(kLayout).body)["solver"]
                                << " (has the fast path got so good that the MIP no longer wins on Freiburg?)";
  EXPECT_EQ(event["city"], kCity);
  EXPECT_EQ(event["version"], fast["version"]);
  EXPECT_NE(event["key"].get<std::string>().find("lengths=vw"), std::string::npos) << event["key"];
  EXPECT_EQ(event["params"]["solver"], "auto");
  EXPECT_EQ(event["params"]["lengths"], "visual-worth");
  EXPECT_EQ(event["params"]["time_limit_s"], fast["params"]["time_limit_s"]);
  EXPECT_EQ(event["solver"]["kind"], "mip");

  // The same request now gets the improved layout, from the cache.
  const auto second = live.get(kLayout);
  ASSERT_EQ(second.status, 200);
  EXPECT_EQ(second.header("x-result-cache"), "hit");
  const auto improved = nlohmann::json::parse(second.body);
  EXPECT_EQ(improved["solver"]["kind"], "mip") << improved["solver"];
  EXPECT_EQ(improved["solver"]["improvement"], "applied");
  EXPECT_EQ(improved["solver"]["mip"]["accepted"], true);
  EXPECT_EQ(improved["quality"], event["quality"]);
  // Kept only as a better map (metro/mip_polish.hpp): fewer bends, no more crossings, the
  // stations' room and their place in the geography kept.
  const auto& q = improved["quality"];
  const auto& f = fast["quality"];
  EXPECT_LT(q["bends"].get<int>(), f["bends"].get<int>());
  EXPECT_LE(q["crossings"].get<int>(), f["crossings"].get<int>());
  EXPECT_LE(q["added_crossings"].get<int>(), f["added_crossings"].get<int>());
  EXPECT_LE(q["order_violations"].get<int>(), f["order_violations"].get<int>());
  EXPECT_GE(q["min_station_gap_ratio"].get<double>(), std::min(f["min_station_gap_ratio"].get<double>(), 0.5) - 1e-3);
  EXPECT_GE(q["min_edge"].get<double>() / q["mean_edge"].get<double>(),
            std::min(f["min_edge"].get<double>() / f["mean_edge"].get<double>(), 0.4) - 1e-3);
  EXPECT_LE(q["mean_displacement"].get<double>(), 1.1 * f["mean_displacement"].get<double>() + 1e-3);
  EXPECT_NE(improved["stations"], fast["stations"]);  // the stations moved
  EXPECT_NE(second.header("etag"), first.header("etag"));
  wait_idle(live, 10s);  // the event goes out just before the job ends
  EXPECT_EQ(gauge(live, "tourmap_layout_improvements_applied"), 1);

  // Layout-space clusters of the default parameters follow the improved layout (no stale tree).
  const auto clusters = live.get("/api/v1/cities/freiburg/clusters?space=layout&bbox=-1e9,-1e9,1e9,1e9");
  EXPECT_EQ(clusters.status, 200) << clusters.body;
}

// The labels of the first zoom where names go round the ring (symbols 12 px across) and the
// stations left unnamed there.
std::pair<std::size_t, std::size_t> named_at_ring_zoom(const nlohmann::json& layout) {
  for (const auto& scale : layout["labels"]["scales"])
    if (scale["mean_edge_px"].get<double>() >= 75)
      return {scale["labels"].size(), scale["unlabelled"].get<std::size_t>()};
  return {0, 0};
}

TEST(LayoutImprovement, LondonGetsRoomForNamesInTheBackground) {
  // London (302 stations) is too large for the MIP, but its centre leaves names out at 75 px:
  // the background improvement makes room for them and announces the layout with more names.
  LiveServer live;
  const auto manifest = live.dir.write("london.json", R"({"cities":[{"id":"london","name":"London","metro":{
    "format":"station-csvs","files":["metro/london.stations.csv","metro/london.lines.csv","metro/london.connections.csv"],
    "attribution":"London Underground geographic data, Wikimedia Commons (CC BY-SA), via nicola/tubemaps"}}]})");
  const auto imported = run_command({kTourmapBin, "import", "manifest", manifest, "--data-dir", data_dir(), "--db", live.db()});
  ASSERT_EQ(imported.exit_code, 0) << imported.output;
  WsClient ws(live.port(), "/api/v1/events");
  ASSERT_EQ(nlohmann::json::parse(ws.receive(5s))["type"], "hello");

  const auto fast = live.get_json("/api/v1/cities/london/layout");
  EXPECT_EQ(fast["solver"]["kind"], "fast");
  EXPECT_EQ(fast["solver"]["improvement"], "scheduled");
  EXPECT_FALSE(fast["solver"].contains("label_room"));  // the first answer spends no time on it
  const auto [fast_named, fast_unnamed] = named_at_ring_zoom(fast);

  // The job computes the fast layout again and makes room in it. On a slow machine (ASan)
  // London's spacing and bend reduction stop at their time budgets, so its layout may differ
  // from the one served first (release: 2-3 of 302 unnamed at 75 px; ASan: 0 seen): what the job
  // did is judged against its own start. It may keep the fast layout only when that start named
  // every station; with any left out it must have made room for some.
  wait_idle(live, kJobWait);
  const auto improved = live.get_json("/api/v1/cities/london/layout");
  if (improved["solver"]["improvement"] == "none") {
    const auto& tried = improved["solver"]["tried"]["label_room"];
    EXPECT_EQ(tried["status"], "not_needed") << improved["solver"];
    EXPECT_EQ(tried["unnamed_before"], 0) << improved["solver"];
    return;
  }
  const auto event = next_event(ws, "layout_improved", 5s);
  ASSERT_FALSE(event.is_null()) << "an improved layout without a layout_improved event";
  EXPECT_EQ(event["city"], "london");
  EXPECT_EQ(event["solver"]["kind"], "fast");  // no MIP over 250 stations
  EXPECT_EQ(event["solver"]["label_room"]["status"], "kept");
  EXPECT_EQ(improved["solver"]["improvement"], "applied");
  const auto& room = improved["solver"]["label_room"];
  EXPECT_GE(room["kept"].get<int>(), 1);
  EXPECT_GT(room["rooms"].get<std::size_t>(), 0u);
  const auto [named, unnamed] = named_at_ring_zoom(improved);
  EXPECT_EQ(room["unnamed_after"].get<std::size_t>(), unnamed);
  if (test::kSlowdown > 1) {
    // Sanitized build: the room-making program stops at its CPU budget 5-20x sooner in work, and
    // a kept round may have named stations only at the larger scales it also counts (seen once:
    // 1 unnamed at 75 px before and after, "kept": 1). Never fewer names at 75 px, though.
    EXPECT_LE(unnamed, room["unnamed_before"].get<std::size_t>()) << room;
  } else {
    EXPECT_LT(unnamed, room["unnamed_before"].get<std::size_t>()) << room;
    EXPECT_EQ(unnamed, 0u) << room;  // issue 14: every station named where symbols are 12 px across
  }
  EXPECT_EQ(named + unnamed, fast_named + fast_unnamed);  // the same stations
  // Each name's type size: the usual one, or the smaller one from 75 px on, as counted.
  const auto& font = improved["labels"]["font"];
  for (const auto& scale : improved["labels"]["scales"]) {
    std::size_t small = 0;
    for (const auto& label : scale["labels"]) {
      ASSERT_GE(label.size(), 10u);
      const double size = label[9].get<double>();
      if (size == font["size_px"].get<double>()) continue;
      EXPECT_EQ(size, font["small_px"].get<double>());
      EXPECT_GE(scale["mean_edge_px"].get<double>(), 75);
      ++small;
    }
    EXPECT_EQ(scale["small"].get<std::size_t>(), small);
  }
  // The layout's guarantees hold against the job's own start (fast London: none added, none
  // violated, smallest gap 0.53 mean edges). Room for names keeps the gap at least min(start,
  // 0.5); under ASan the job's spacing may stop at its time budget short of 0.5 (seen: 0.43), and
  // then that is the floor.
  const auto& q = improved["quality"];
  EXPECT_EQ(q["octilinear_share"], 1.0);
  EXPECT_EQ(q["added_crossings"], 0);
  EXPECT_EQ(q["order_violations"], 0);
  const auto& spacing = improved["fast_path"]["spacing"];
  const double start_gap = spacing["gap_after"].get<double>();
  const double floor = test::kSlowdown > 1 ? std::min(start_gap, 0.5) : 0.5;
  EXPECT_GE(q["min_station_gap_ratio"].get<double>(), floor - 1e-3) << spacing;
}

TEST(LayoutImprovement, AnImprovementThatDoesNotWinSaysWhatItTried) {
  // 50 ms of CBC find no layout with fewer bends, and Freiburg's names need no room: the fast
  // layout stays, marked "none", with the job's reports.
  LiveServer live({"--improve-mip", "0.05"});
  import_freiburg(live);
  const auto fast = live.get_json(kLayout);
  ASSERT_EQ(fast["solver"]["improvement"], "scheduled");
  const auto until = Clock::now() + kJobWait;
  while (Clock::now() < until && gauge(live, "tourmap_layout_improvements_not_better") < 1) std::this_thread::sleep_for(100ms);
  ASSERT_EQ(gauge(live, "tourmap_layout_improvements_not_better"), 1);
  const auto kept = live.get_json(kLayout);
  EXPECT_EQ(kept["solver"]["improvement"], "none");
  EXPECT_EQ(kept["solver"]["kind"], "fast");
  EXPECT_EQ(kept["stations"], fast["stations"]);  // the same layout
  const auto& tried = kept["solver"]["tried"];
  ASSERT_TRUE(tried.contains("mip")) << kept["solver"];
  EXPECT_FALSE(tried["mip"].value("accepted", false)) << tried;
  EXPECT_EQ(tried["label_room"]["status"], "not_needed") << tried;
  // Served as the body was, and not scheduled again.
  EXPECT_EQ(live.get_json(kLayout)["solver"], kept["solver"]);
  EXPECT_EQ(gauge(live, "tourmap_layout_improvements_scheduled"), 1);
}

TEST(LayoutImprovement, FastAndMipRequestsScheduleNothing) {
  LiveServer live;
  import_freiburg(live);
  WsClient ws(live.port(), "/api/v1/events");
  ASSERT_EQ(nlohmann::json::parse(ws.receive(5s))["type"], "hello");

  const auto fast = live.get_json(kLayout + "?solver=fast");
  EXPECT_EQ(fast["solver"]["kind"], "fast");
  EXPECT_EQ(fast["solver"]["improvement"], "none");
  // solver=mip stays synchronous: the answer is the polished layout, nothing follows.
  const auto mip = live.get_json(kLayout + "?solver=mip&time_limit_s=5");
  EXPECT_TRUE(mip["solver"].contains("mip")) << mip["solver"];
  EXPECT_EQ(mip["solver"]["improvement"], "none");
  // Nothing was scheduled, and no event comes.
  EXPECT_EQ(gauge(live, "tourmap_layout_improvements_scheduled"), 0);
  EXPECT_TRUE(next_event(ws, "layout_improved", 3s).is_null());
  EXPECT_EQ(gauge(live, "tourmap_layout_improvements_scheduled"), 0);
}

TEST(LayoutImprovement, RepeatedDefaultRequestsScheduleOnce) {
  LiveServer live(kWinnable);
  import_freiburg(live);
  for (int i = 0; i < 5; ++i) {
    const auto l = live.get_json(kLayout);
    const auto state = l["solver"]["improvement"].get<std::string>();
    // Scheduled until the MIP has run, then the improved layout.
    EXPECT_TRUE(state == "scheduled" || state == "applied") << state;
  }
  wait_idle(live, kJobWait);
  EXPECT_EQ(gauge(live, "tourmap_layout_improvements_scheduled"), 1);
  if (mip_was_no_better(live)) GTEST_SKIP() << "the MIP's optimum was no better than this run's fast layout";
  const auto solver = live.get_json(kLayout)["solver"];
  EXPECT_EQ(solver["improvement"], "applied") << solver;  // else solver.tried says what the job tried
  EXPECT_EQ(gauge(live, "tourmap_layout_improvements_scheduled"), 1);
}

TEST(LayoutImprovement, ImprovementOfAnOlderCityVersionIsDropped) {
  LiveServer live;
  import_freiburg(live);
  WsClient ws(live.port(), "/api/v1/events");
  ASSERT_EQ(nlohmann::json::parse(ws.receive(5s))["type"], "hello");
  // Vienna's improvement goes first and takes a while (fast path, then CBC for up to its 10 s
  // limit in a child process); Freiburg's waits behind it, and the city is imported again
  // meanwhile.
  ASSERT_EQ(live.get_json("/api/v1/cities/vienna/layout")["solver"]["improvement"], "scheduled");
  const auto old = live.get_json(kLayout);
  ASSERT_EQ(old["solver"]["improvement"], "scheduled");
  import_freiburg(live);
  wait_idle(live, kJobWait);
  EXPECT_EQ(gauge(live, "tourmap_layout_improvements_stale"), 1);
  // Whatever Vienna's MIP did, no event names Freiburg.
  for (auto ev = next_event(ws, "layout_improved", 1s); !ev.is_null(); ev = next_event(ws, "layout_improved", 1s))
    EXPECT_NE(ev["city"], kCity) << ev;
  // The new version is a new layout, scheduled anew.
  const auto fresh = live.get_json(kLayout);
  EXPECT_GT(fresh["version"].get<long long>(), old["version"].get<long long>());
  EXPECT_EQ(fresh["solver"]["improvement"], "scheduled");
}

TEST(LayoutImprovement, ShutdownStopsARunningImprovement) {
  LiveServer live;
  ASSERT_EQ(live.get_json("/api/v1/cities/vienna/layout")["solver"]["improvement"], "scheduled");
  std::this_thread::sleep_for(200ms);  // the job is running: the fast path again, or CBC
  EXPECT_EQ(gauge(live, "tourmap_layout_improvements_running"), 1);
  const auto started = Clock::now();
  const auto stopped = live.server->stop();
  const double took_s = std::chrono::duration<double>(Clock::now() - started).count();
  EXPECT_EQ(stopped.exit_code, 0) << stopped.output;
  EXPECT_NE(stopped.output.find("shutdown: done"), std::string::npos) << stopped.output;
  // The CBC child is killed at once (its budget and grace would be 13 s).
  EXPECT_LT(took_s, 2.0) << stopped.output;
  EXPECT_EQ(stopped.output.find("failed"), std::string::npos) << stopped.output;
}

TEST(ServeOptions, ImproveMipOutsideZeroTo600SecondsIsRefusedAtStart) {
  TempDir dir;
  const std::string db = dir.file("t.db");
  for (const std::string value : {"-1", "601", "nan", "inf", "ten"}) {
    auto r = run_command({kTourmapBin, "serve", "--db", db, "--port", "0", "--improve-mip", value});
    EXPECT_EQ(r.exit_code, 2) << value << ": " << r.output;
    EXPECT_NE(r.output.find("improve-mip"), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace tourmap::test
