// The metro map endpoints against a real server: layout, visual worth, clusters, bad input.

#include "live_server_suite.hpp"
#include "slowdown.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

namespace tourmap::test {
namespace {

class MetroApi : public LiveServerSuite<MetroApi> {};

// Horizontal, vertical or diagonal up to the 1 mm rounding of the layout coordinates (each end
// off by up to 0.5 mm per axis, so |dx|, |dy| or their difference may be off by 1 mm), and
// within the metric tool's 1 degree of it (a short leg rounded to decimetres was not).
bool octilinear(const nlohmann::json& a, const nlohmann::json& b) {
  const double dx = std::abs(b[0].get<double>() - a[0].get<double>()), dy = std::abs(b[1].get<double>() - a[1].get<double>());
  const double slack = 0.001 + 1e-9;
  const double degrees = std::atan2(dy, dx) * 180 / M_PI;  // 0..90
  const double off = std::min({degrees, std::abs(degrees - 45), 90 - degrees});
  return (dx <= slack || dy <= slack || std::abs(dx - dy) <= slack) && off <= 1.0;
}

TEST_F(MetroApi, LayoutIsOctilinearWithWarpedPoisAndAReport) {
  auto r = live->get("/api/v1/cities/vienna/layout?lengths=visual-worth&solver=auto");
  ASSERT_EQ(r.status, 200) << r.body;
  auto l = nlohmann::json::parse(r.body);
  EXPECT_EQ(l["stations"]["features"].size(), 98u);
  EXPECT_EQ(l["edges"]["features"].size(), 105u);
  EXPECT_EQ(l["pois"]["features"].size(), 63u);
  for (const auto& e : l["edges"]["features"]) {
    const auto& c = e["geometry"]["coordinates"];
    for (std::size_t i = 1; i < c.size(); ++i) EXPECT_TRUE(octilinear(c[i - 1], c[i])) << c << e["properties"];
  }
  const auto& q = l["quality"];
  EXPECT_EQ(q["octilinear_share"], 1.0);
  EXPECT_LE(q["crossings"].get<int>(), q["geo_crossings"].get<int>());
  EXPECT_EQ(q["order_violations"], 0);
  EXPECT_GT(q["min_edge"].get<double>(), 0.0);
  // The metric tool's figures: bends along lines between interchanges, never more than the
  // bends counted per edge and through every station.
  ASSERT_TRUE(q.contains("compare"));
  EXPECT_LE(q["compare"]["bends"].get<int>(), q["bends"].get<int>());
  EXPECT_GT(q["compare"]["displacement"].get<double>(), 0.0);
  EXPECT_EQ(q["compare"]["octilinear_share"], 1.0);
  EXPECT_TRUE(l["solver"]["kind"] == "fast" || l["solver"]["kind"] == "mip");
  EXPECT_EQ(l["mesh"]["geo"].size(), l["mesh"]["layout"].size());
  EXPECT_GT(l["outline"]["layout"].size(), 2u);
  EXPECT_TRUE(l["timing_ms"].contains("visual_worth"));
  EXPECT_EQ(l["params"]["rank"], "proxy");  // Vienna's sights carry no rank
  // Uniform lengths give a different layout; the same request again comes from the cache.
  auto uniform = live->get("/api/v1/cities/vienna/layout?lengths=uniform&solver=fast");
  ASSERT_EQ(uniform.status, 200);
  EXPECT_NE(nlohmann::json::parse(uniform.body)["edges"], l["edges"]);
  auto again = live->get("/api/v1/cities/vienna/layout?lengths=uniform&solver=fast");
  EXPECT_EQ(again.header("x-result-cache"), "hit");
  EXPECT_EQ(again.body, uniform.body);
}

// The served station names: at every zoom no two overlap (nor at the zooms a client shows a
// placement at, up to the next one's), and none lies on an edge (half its bundle of parallel
// lines wide); more zoom, at least as many names.
TEST_F(MetroApi, StationNamesNeverOverlap) {
  auto r = live->get("/api/v1/cities/vienna/layout");
  ASSERT_EQ(r.status, 200) << r.body;
  auto l = nlohmann::json::parse(r.body);
  ASSERT_TRUE(l.contains("labels"));
  const auto& labels = l["labels"];
  const auto& stations = l["stations"]["features"];
  const double spacing = labels["line_spacing_px"].get<double>();
  ASSERT_GE(labels["scales"].size(), 3u);
  std::size_t previous = 0;
  struct Box {
    double x0, y0, x1, y1;
  };
  // The boxes of a scale's names at `k` px per metre, in metres (y north).
  const auto boxes_at = [&](const nlohmann::json& scale, double k) {
    std::vector<Box> boxes;
    for (const auto& label : scale["labels"]) {
      const auto& at = stations.at(label[0].get<std::size_t>())["geometry"]["coordinates"];
      const double x = at[0].get<double>(), y = at[1].get<double>();
      boxes.push_back({x + label[1].get<double>() / k, y - label[4].get<double>() / k, x + label[3].get<double>() / k,
                       y - label[2].get<double>() / k});
    }
    return boxes;
  };
  const auto& scales = labels["scales"];
  for (std::size_t n = 0; n < scales.size(); ++n) {
    const auto& scale = scales[n];
    const double k = scale["px_per_m"].get<double>();  // px per metre
    const double next = n + 1 < scales.size() ? scales[n + 1]["px_per_m"].get<double>() : 4 * k;
    for (int step = 0; step <= 8; ++step) {
      const double zoom = k + (next - k) * step / 8 * (1 - 1e-6);
      const auto boxes = boxes_at(scale, zoom);
      for (std::size_t i = 0; i < boxes.size(); ++i)
        for (std::size_t j = i + 1; j < boxes.size(); ++j) {
          const auto &a = boxes[i], &b = boxes[j];
          EXPECT_FALSE(a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1)
              << "labels " << i << " and " << j << " of scale " << n << " at " << zoom << " px/m";
        }
    }
    const auto boxes = boxes_at(scale, k);
    for (const auto& e : l["edges"]["features"]) {
      const double half = e["properties"]["lines"].size() * spacing / 2 / k;
      const auto& c = e["geometry"]["coordinates"];
      for (std::size_t s = 1; s < c.size(); ++s) {
        // Octilinear pieces: sample the segment every metre-ish and test the thickened point.
        const double x0 = c[s - 1][0], y0 = c[s - 1][1], x1 = c[s][0], y1 = c[s][1];
        const int steps = std::max(1, static_cast<int>(std::hypot(x1 - x0, y1 - y0) / (half + 1e-9)));
        for (int t = 0; t <= steps; ++t) {
          const double px = x0 + (x1 - x0) * t / steps, py = y0 + (y1 - y0) * t / steps;
          for (const auto& b : boxes)
            EXPECT_FALSE(px > b.x0 + half && px < b.x1 - half && py > b.y0 + half && py < b.y1 - half)
                << "a label over edge " << e["properties"]["from"] << " at scale " << scale["mean_edge_px"];
        }
      }
    }
    EXPECT_GE(scale["labels"].size(), previous);
    previous = scale["labels"].size();
  }
  EXPECT_EQ(labels["font"]["family"], "DejaVu Sans Condensed");
}

TEST_F(MetroApi, PostLayoutAndMip) {
  auto r = http_request(live->port(), "POST", "/api/v1/cities/lisbon/layout", {{"Content-Type", "application/json"}},
                        R"({"solver":"mip","lengths":"uniform","time_limit_s":3})");
  ASSERT_EQ(r.status, 200) << r.body;
  auto l = nlohmann::json::parse(r.body);
  EXPECT_TRUE(l["solver"].contains("mip")) << l["solver"];
  EXPECT_FALSE(l["solver"]["mip"]["status"].get<std::string>().empty());
  EXPECT_EQ(l["quality"]["octilinear_share"], 1.0);
  // The time limit, plus the child's grace and the stages after the solver (warp, names), which
  // run test::kSlowdown times slower under sanitizers (4527 ms there once, against 4500).
  EXPECT_LE(l["timing_ms"]["total"].get<double>(), 3000.0 + 1500.0 * test::kSlowdown);
}

TEST_F(MetroApi, VisualWorthRaster) {
  auto v = live->get_json("/api/v1/cities/vienna/visual-worth?width=32&height=16");
  EXPECT_EQ(v["values"].size(), 32u * 16u);
  double max = 0;
  for (const auto& x : v["values"]) max = std::max(max, x.get<double>());
  EXPECT_EQ(max, 1.0);  // normalised
  EXPECT_EQ(v["stations"].size(), 98u);
  EXPECT_EQ(v["pois"], 63);
  auto none = live->get_json("/api/v1/cities/lisbon/visual-worth?width=4&height=4");  // no POIs
  EXPECT_EQ(none["max"], 0.0);
}

TEST_F(MetroApi, ClustersRespectTheWindowAndChangeWithIt) {
  auto all = live->get_json("/api/v1/cities/vienna/clusters?m=5");
  EXPECT_EQ(all["space"], "geo");
  // The whole extent is refined to 2m active clusters: m shown and m previews.
  EXPECT_EQ(all["clusters"].size(), 5u);
  EXPECT_EQ(all["previews"].size(), 5u);
  EXPECT_GE(all["active"].get<int>(), 10);
  double sum = 0;
  for (const auto& c : all["clusters"]) {
    sum += c["prominence"].get<double>();
    EXPECT_FALSE(c["representative"]["name"].get<std::string>().empty());
  }
  EXPECT_LE(sum, 1.0 + 1e-9);
  // A small window in the inner city: every cluster centre lies inside it.
  auto inner = live->get_json("/api/v1/cities/vienna/clusters?bbox=16.355,48.200,16.385,48.215&m=10");
  for (const auto& c : inner["clusters"]) {
    double lon = c["center"][0], lat = c["center"][1];
    EXPECT_TRUE(lon >= 16.355 && lon <= 16.385 && lat >= 48.200 && lat <= 48.215) << c;
  }
  EXPECT_NE(inner["clusters"], all["clusters"]);
  // Layout space: the window is in the layout's frame.
  auto layout = live->get_json("/api/v1/cities/vienna/layout");
  double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
  for (const auto& p : layout["pois"]["features"]) {
    double x = p["geometry"]["coordinates"][0], y = p["geometry"]["coordinates"][1];
    x0 = std::min(x0, x);
    y0 = std::min(y0, y);
    x1 = std::max(x1, x);
    y1 = std::max(y1, y);
  }
  auto in_layout = live->get_json("/api/v1/cities/vienna/clusters?space=layout&bbox=" + std::to_string(x0 - 1) + "," +
                                  std::to_string(y0 - 1) + "," + std::to_string(x1 + 1) + "," + std::to_string(y1 + 1));
  EXPECT_EQ(in_layout["space"], "layout");
  EXPECT_EQ(in_layout["clusters"].size(), 10u);
  // A representative stands where the layout put its POI (rounded to 0.1 m).
  std::map<std::string, std::pair<double, double>> poi_at;
  for (const auto& p : layout["pois"]["features"])
    poi_at[p["properties"]["id"].get<std::string>()] = {p["geometry"]["coordinates"][0], p["geometry"]["coordinates"][1]};
  for (const auto& c : in_layout["clusters"]) {
    const auto& rep = c["representative"];
    ASSERT_TRUE(poi_at.count(rep["id"].get<std::string>())) << rep;
    auto [x, y] = poi_at[rep["id"].get<std::string>()];
    EXPECT_NEAR(rep["position"][0].get<double>(), x, 0.1) << rep;
    EXPECT_NEAR(rep["position"][1].get<double>(), y, 0.1) << rep;
  }
}

// Clusters and visual worth are computed per request; their bodies must still repeat, so a
// client revalidating with If-None-Match gets a 304 (the compute time is in Server-Timing).
TEST_F(MetroApi, ComputedAnswersRevalidateWithTheirEtag) {
  const std::pair<std::string, std::string> paths[] = {
      {"/api/v1/cities/vienna/clusters?m=4&bbox=16.3,48.18,16.4,48.23", "/api/v1/cities/vienna/clusters?m=5"},
      {"/api/v1/cities/vienna/visual-worth?width=8&height=8", "/api/v1/cities/vienna/visual-worth?width=8&height=9"}};
  for (const auto& [path, other_path] : paths) {
    SCOPED_TRACE(path);
    auto first = live->get(path);
    ASSERT_EQ(first.status, 200) << first.body;
    EXPECT_EQ(first.header("server-timing").rfind("compute;dur=", 0), 0u) << first.header("server-timing");
    const auto etag = first.header("etag");
    ASSERT_FALSE(etag.empty());
    auto again = live->get(path, {{"If-None-Match", etag}});
    EXPECT_EQ(again.status, 304);
    EXPECT_TRUE(again.body.empty());
    auto other = live->get(other_path, {{"If-None-Match", etag}});  // another answer: a new body
    EXPECT_EQ(other.status, 200);
  }
}

TEST_F(MetroApi, BadInputNamesTheField) {
  expect_error(live->get("/api/v1/cities/atlantis/layout"), 404, "id");
  expect_error(live->get("/api/v1/cities/vienna/layout?lengths=long"), 400, "lengths");
  expect_error(live->get("/api/v1/cities/vienna/layout?solver=gurobi"), 400, "solver");
  expect_error(live->get("/api/v1/cities/vienna/layout?time_limit_s=0"), 400, "time_limit_s");
  expect_error(live->get("/api/v1/cities/vienna/layout?time_limit_s=nan"), 400, "time_limit_s");
  expect_error(live->get("/api/v1/cities/vienna/layout?rank=data"), 400, "rank");  // no ranks in the data
  expect_error(live->get("/api/v1/cities/vienna/layout?k=-5"), 400, "k");
  expect_error(http_request(live->port(), "POST", "/api/v1/cities/vienna/layout", {{"Content-Type", "application/json"}},
                            R"({"lengths": 5})"),
               400, "lengths");
  expect_error(http_request(live->port(), "POST", "/api/v1/cities/vienna/layout", {{"Content-Type", "application/json"}},
                            R"({"colour": "red"})"),
               400, "colour");
  expect_error(live->get("/api/v1/cities/vienna/clusters?m=0"), 400, "m");
  expect_error(live->get("/api/v1/cities/vienna/clusters?m=100000"), 400, "m");
  expect_error(live->get("/api/v1/cities/vienna/clusters?bbox=16.4,48.2,16.3,48.3"), 400, "bbox");
  expect_error(live->get("/api/v1/cities/vienna/clusters?bbox=nan,48.2,16.3,48.3"), 400, "bbox");
  expect_error(live->get("/api/v1/cities/vienna/clusters?space=tokyo"), 400, "space");
  expect_error(live->get("/api/v1/cities/vienna/clusters?space=layout"), 400, "bbox");
  expect_error(live->get("/api/v1/cities/vienna/clusters?space=layout&bbox=5,5,1,1"), 400, "bbox");
  expect_error(live->get("/api/v1/cities/vienna/visual-worth?width=100000"), 400, "width");
  expect_error(live->get("/api/v1/cities/vienna/visual-worth?height=0"), 400, "height");
}

}  // namespace
}  // namespace tourmap::test
