// The deformation endpoints against a real server: the three applications, the methods, the
// factorization cache while "dragging", and bad input.

#include "live_server_suite.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <queue>
#include <utility>
#include <vector>

namespace tourmap::test {
namespace {

class DeformApi : public LiveServerSuite<DeformApi> {
 protected:
  static void SetUpTestSuite() {
    LiveServerSuite::SetUpTestSuite();
    topology = new nlohmann::json(live->get_json("/api/v1/roads/west-oakland?format=topology"));
  }
  static void TearDownTestSuite() {
    delete topology;
    topology = nullptr;
    LiveServerSuite::TearDownTestSuite();
  }
  static HttpResult post(const std::string& app, const nlohmann::json& body) {
    return http_request(live->port(), "POST", "/api/v1/deform/" + app, {{"Content-Type", "application/json"}},
                        body.dump());
  }
  static nlohmann::json ok(const std::string& app, const nlohmann::json& body) {
    auto r = post(app, body);
    EXPECT_EQ(r.status, 200) << r.body;
    return nlohmann::json::parse(r.body);
  }
  // A path of `n` consecutive nodes along the longest way.
  static std::vector<std::int64_t> route(std::size_t n) {
    const nlohmann::json* best = nullptr;
    for (const auto& w : (*topology)["ways"])
      if (!best || w["nodes"].size() > (*best)["nodes"].size()) best = &w;
    std::vector<std::int64_t> ids;
    for (std::size_t i = 0; i < n && i < (*best)["nodes"].size(); ++i)
      ids.push_back((*topology)["node_ids"][(*best)["nodes"][i].get<std::size_t>()]);
    return ids;
  }
  static nlohmann::json focus_body(double lon, double lat) {
    return {{"roads", "west-oakland"},
            {"regions", {{{"center", {lon, lat}}, {"radius_m", 300}, {"scale", 3}}}},
            {"output", {{"roads", "positions"}, {"grid", false}}}};
  }
  static inline nlohmann::json* topology = nullptr;
};

TEST_F(DeformApi, FocusMovesRoadsAndReportsStats) {
  auto out = ok("focus", {{"roads", "west-oakland"},
                          {"regions", {{{"center", {-122.303, 37.811}}, {"radius_m", 400}, {"scale", 3}}}},
                          {"grid", {{"kind", "adaptive"}, {"base", 10}, {"depth", 3}}}});
  const auto& s = out["stats"];
  EXPECT_GT(s["scaled_edges"].get<int>(), 0);
  EXPECT_LT(s["residue"].get<double>(), s["residue_rest"].get<double>());
  EXPECT_TRUE(s["converged"].get<bool>());
  EXPECT_GT(s["unknowns"].get<int>(), 0);
  EXPECT_GT(s["quads"].get<int>(), 0);
  EXPECT_EQ(out["roads"]["type"], "FeatureCollection");
  EXPECT_EQ(out["roads"]["features"].size(), 31u);
  EXPECT_EQ(out["grid"]["before"].size(), out["grid"]["after"].size());
  EXPECT_EQ(out["attribution"].size(), 1u);
  // The roads moved: compare with the stored network.
  auto plain = live->get_json("/api/v1/roads/west-oakland");
  EXPECT_NE(plain["features"][0]["geometry"], out["roads"]["features"][0]["geometry"]);
}

TEST_F(DeformApi, DraggingReusesTheFactorization) {
  auto first = ok("focus", focus_body(-122.305, 37.810));
  auto moved_body = focus_body(-122.300, 37.812);
  moved_body["map_points"] = {{-122.300, 37.812}, {-122.400, 37.9}};
  auto second = ok("focus", moved_body);
  ASSERT_EQ(second["mapped_points"].size(), 2u);  // the focus centre, and a point outside the map
  EXPECT_NEAR(second["mapped_points"][0][0].get<double>(), -122.300, 0.01);
  EXPECT_GT(second["version"].get<int>(), 0);
  EXPECT_EQ(second["stats"]["cache"], "hit");
  EXPECT_EQ(second["stats"]["factor_ms"], 0.0);
  EXPECT_NE(first["positions"], second["positions"]);
  EXPECT_EQ(second["positions"].size(), 2 * (*topology)["node_ids"].size());
  // The identical request again comes from the result cache.
  auto repeat = post("focus", moved_body);
  EXPECT_EQ(repeat.header("x-result-cache"), "hit");
  EXPECT_EQ(nlohmann::json::parse(repeat.body)["positions"], second["positions"]);
}

// The binary positions (api/positions_binary.hpp): the JSON answer's positions to float32
// offsets from a float64 origin, its other fields as JSON in front.
TEST_F(DeformApi, PositionsComeAsBinaryWhenAskedFor) {
  const auto body = focus_body(-122.302, 37.809);
  const auto json = ok("focus", body);
  const auto binary_post = [&] {
    return http_request(live->port(), "POST", "/api/v1/deform/focus",
                        {{"Content-Type", "application/json"}, {"Accept", "application/octet-stream"}}, body.dump());
  };
  const auto r = binary_post();
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.header("content-type"), "application/octet-stream");
  const std::string& b = r.body;
  ASSERT_GE(b.size(), 32u);
  const auto u32 = [&](std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
  };
  const auto f64 = [&](std::size_t at) {
    double v;
    std::memcpy(&v, b.data() + at, 8);
    return v;
  };
  EXPECT_EQ(b.substr(0, 4), "TMDP");
  EXPECT_EQ(u32(4), 1u);
  const std::size_t json_bytes = u32(8), points = u32(12);
  ASSERT_EQ(points, (*topology)["node_ids"].size());
  const std::size_t start = (32 + json_bytes + 3) / 4 * 4;
  ASSERT_EQ(b.size(), start + 8 * points);
  const auto meta = nlohmann::json::parse(b.substr(32, json_bytes));
  EXPECT_FALSE(meta.contains("positions"));
  EXPECT_EQ(meta["stats"]["residue"], json["stats"]["residue"]);
  EXPECT_EQ(meta["roads_id"], "west-oakland");
  const double lon0 = f64(16), lat0 = f64(24);
  const auto& expected = json["positions"];
  double worst = 0;
  for (std::size_t i = 0; i < points; ++i)
    for (std::size_t k = 0; k < 2; ++k) {
      float offset;
      std::memcpy(&offset, b.data() + start + 8 * i + 4 * k, 4);
      worst = std::max(worst, std::abs((k ? lat0 : lon0) + offset - expected[2 * i + k].get<double>()));
    }
  EXPECT_LT(worst, 2e-7);  // the JSON's 7 decimals, and float32 over a few km: well under 0.1 m
  // From the result cache in the same format; JSON where JSON is preferred.
  const auto again = binary_post();
  EXPECT_EQ(again.header("x-result-cache"), "hit");
  EXPECT_EQ(again.header("content-type"), "application/octet-stream");
  EXPECT_EQ(again.body, r.body);
  const auto prefer_json = http_request(live->port(), "POST", "/api/v1/deform/focus",
                                        {{"Content-Type", "application/json"},
                                         {"Accept", "application/octet-stream;q=0.5, application/json"}},
                                        body.dump());
  EXPECT_EQ(prefer_json.status, 200);
  EXPECT_EQ(prefer_json.header("content-type"), "application/json");
  // Only positions come as binary.
  auto geojson = body;
  geojson["output"]["roads"] = "geojson";
  const auto refused = http_request(live->port(), "POST", "/api/v1/deform/focus",
                                    {{"Content-Type", "application/json"}, {"Accept", "application/octet-stream"}},
                                    geojson.dump());
  EXPECT_EQ(refused.status, 406);
  EXPECT_EQ(nlohmann::json::parse(refused.body)["error"]["field"], "output.roads");
}

TEST_F(DeformApi, EveryMethodAndSolverAnswers) {
  for (nlohmann::json grid : {nlohmann::json{{"kind", "uniform"}, {"n", 20}}, nlohmann::json{{"kind", "edges"}},
                              nlohmann::json{{"kind", "adaptive"}, {"depth", 2}}})
    for (std::string solver : {"cholesky", "cg"}) {
      auto body = focus_body(-122.303, 37.811);
      body["grid"] = grid;
      body["solver"] = solver;
      body["relax"] = true;
      body["check_crossings"] = true;
      auto out = ok("focus", body);
      EXPECT_EQ(out["stats"]["solver"], solver);
      EXPECT_TRUE(out["stats"]["crossings_added"].is_number());
      if (grid["kind"] == "edges") {
        EXPECT_TRUE(out["grid"].is_null());
      }
    }
}

TEST_F(DeformApi, MentalMapPullsGuidesToTargets) {
  auto ids = route(3);
  auto node = ids[1];
  // Move one vertex 100 m north (about 0.0009 degrees).
  std::size_t index = 0;
  while ((*topology)["node_ids"][index] != node) ++index;
  double lon = (*topology)["positions"][2 * index], lat = (*topology)["positions"][2 * index + 1];
  auto out = ok("mental", {{"roads", "west-oakland"},
                           {"guides", {{{"vertex", node}, {"target", {lon, lat + 0.0009}}},
                                       {{"point", {-122.31, 37.805}}, {"target", {-122.31, 37.806}}}}},
                           {"grid", {{"kind", "edges"}}}});
  ASSERT_EQ(out["guides"].size(), 2u);
  for (const auto& g : out["guides"]) {
    double moved = g["to"][1].get<double>() - g["from"][1].get<double>();
    double wanted = g["target"][1].get<double>() - g["from"][1].get<double>();
    EXPECT_GT(moved / wanted, 0.5) << g;  // most of the way there
  }
  EXPECT_EQ(out["stats"]["guides"], 2);
}

TEST_F(DeformApi, DestinationMapFollowsTheSketch) {
  auto ids = route(5);
  auto out = ok("destination", {{"roads", "west-oakland"},
                                {"route", ids},
                                {"sketch", {{-122.310, 37.805}, {-122.300, 37.805}, {-122.300, 37.815}}},
                                {"simplify_m", 5}});
  EXPECT_EQ(out["guides"].size(), ids.size());
  EXPECT_LT(out["stats"]["residue"].get<double>(), out["stats"]["residue_rest"].get<double>());
}

TEST_F(DeformApi, InlineRoads) {
  nlohmann::json fc = {{"type", "FeatureCollection"},
                       {"features",
                        {{{"type", "Feature"},
                          {"properties", {{"highway", "residential"}}},
                          {"geometry", {{"type", "LineString"},
                                        {"coordinates", {{7.0, 43.0}, {7.01, 43.0}, {7.02, 43.01}}}}}},
                         {{"type", "Feature"},
                          {"properties", nullptr},
                          {"geometry", {{"type", "LineString"}, {"coordinates", {{7.01, 43.0}, {7.01, 43.02}}}}}}}}};
  auto out = ok("focus", {{"roads", fc}, {"regions", {{{"center", {7.01, 43.0}}, {"radius_m", 500}, {"scale", 2}}}}});
  EXPECT_EQ(out["roads_id"], "inline");
  EXPECT_EQ(out["stats"]["road_edges"], 3);
}

TEST_F(DeformApi, BadInputNamesTheField) {
  auto focus = [](nlohmann::json regions) {
    return nlohmann::json{{"roads", "west-oakland"}, {"regions", regions}};
  };
  nlohmann::json c = {-122.303, 37.811};
  expect_error(post("focus", {{"regions", {{{"center", c}, {"radius_m", 100}, {"scale", 2}}}}}), 400, "roads");
  expect_error(post("focus", {{"roads", "atlantis"}, {"regions", {{{"center", c}, {"radius_m", 100}, {"scale", 2}}}}}),
               404, "roads");
  expect_error(post("focus", {{"roads", 5}, {"regions", nlohmann::json::array()}}), 400, "roads");
  expect_error(post("focus", {{"roads", "../etc"}, {"regions", {{{"center", c}, {"radius_m", 100}, {"scale", 2}}}}}), 404,
               "roads");
  expect_error(post("focus", focus(nlohmann::json::array())), 400, "regions");
  expect_error(post("focus", focus({{{"center", c}, {"radius_m", 100}, {"scale", 0}}})), 400, "regions[0].scale");
  expect_error(post("focus", focus({{{"center", c}, {"radius_m", 100}, {"scale", -2}}})), 400, "regions[0].scale");
  expect_error(post("focus", focus({{{"center", c}, {"radius_m", 100}, {"scale", 51}}})), 400, "regions[0].scale");
  expect_error(post("focus", focus({{{"center", c}, {"radius_m", 100}, {"scale", 1e-300}}})), 400, "regions[0].scale");
  expect_error(post("focus", focus({{{"center", c}, {"radius_m", 100}, {"scale", "3"}}})), 400, "regions[0].scale");
  expect_error(post("focus", focus({{{"center", c}, {"scale", 3}}})), 400, "regions[0].radius_m");
  expect_error(post("focus", focus({{{"center", {200, 0}}, {"radius_m", 10}, {"scale", 3}}})), 400, "regions[0].center");
  expect_error(post("focus", focus({{{"polygon", {{0, 0}, {1, 1}, {1, 0}, {0, 1}}}, {"scale", 3}}})), 400,
               "regions[0].polygon");  // self-intersecting
  expect_error(post("focus", focus({{{"polygon", {{0, 0}, {1, 1}, {2, 2}}}, {"scale", 3}}})), 400,
               "regions[0].polygon");  // zero area
  expect_error(post("focus", focus({{{"center", c}, {"radius_m", 10}, {"polygon", {{0, 0}, {1, 0}, {1, 1}}}, {"scale", 2}}})),
               400, "regions[0]");
  auto body = focus({{{"center", c}, {"radius_m", 100}, {"scale", 2}}});
  body["grid"] = {{"kind", "adaptive"}, {"depth", 9}};
  expect_error(post("focus", body), 400, "grid.depth");
  body["grid"] = {{"kind", "hexagonal"}};
  expect_error(post("focus", body), 400, "grid.kind");
  body["grid"] = {{"kind", "uniform"}, {"n", 256}, {"base", 3}};
  expect_error(post("focus", body), 400, "grid.base");
  body["grid"] = {{"kind", "adaptive"}, {"base", 64}, {"depth", 6}, {"c", 0}};
  expect_error(post("focus", body), 413, "grid");  // finer than the lattice limit
  body["grid"] = {{"kind", "uniform"}, {"n", 256}};
  expect_error(post("focus", body), 413, "grid");  // too big for the direct solver
  body.erase("grid");
  body["solver"] = "magic";
  expect_error(post("focus", body), 400, "solver");
  body.erase("solver");
  body["colour"] = "red";
  expect_error(post("focus", body), 400, "colour");

  expect_error(post("mental", {{"roads", "west-oakland"}, {"guides", {{{"vertex", 1}, {"target", c}}}}}), 400,
               "guides[0].vertex");  // no such node
  expect_error(post("mental", {{"roads", "west-oakland"}, {"guides", {{{"target", c}}}}}), 400, "guides[0].vertex");
  expect_error(post("mental", {{"roads", "west-oakland"}, {"guides", {{{"vertex", route(1)[0]}}}}}), 400,
               "guides[0].target");
  auto ids = route(4);
  expect_error(post("destination", {{"roads", "west-oakland"}, {"route", ids}, {"sketch", {c}}}), 400, "sketch");
  expect_error(post("destination", {{"roads", "west-oakland"}, {"route", {ids[0], ids[2]}}, {"sketch", {c, c}}}), 400,
               "route[1]");  // not adjacent
  expect_error(post("destination", {{"roads", "west-oakland"}, {"route", {ids[0], ids[1], ids[0]}}, {"sketch", {c, c}}}),
               400, "route[2]");  // repeats
  expect_error(post("destination", {{"roads", "west-oakland"}, {"route", {ids[0]}}, {"sketch", {c, c}}}), 400, "route");

  nlohmann::json empty = {{"type", "FeatureCollection"}, {"features", nlohmann::json::array()}};
  expect_error(post("focus", {{"roads", empty}, {"regions", {{{"center", c}, {"radius_m", 100}, {"scale", 2}}}}}), 400,
               "roads");
  auto nan = http_request(live->port(), "POST", "/api/v1/deform/focus", {{"Content-Type", "application/json"}},
                          R"({"roads":"west-oakland","regions":[{"center":[NaN,1],"radius_m":1,"scale":2}]})");
  expect_error(nan, 400, "body");
}

// The client's three demo requests (a focus lens where the user first clicks, a mental map pulling
// vertices onto a circle, a route pulled onto a straight sketch), as probes of the whole network:
// by default no grid quad is left folded and no road crosses another it did not cross; asked
// for the raw solve (relax false), the same requests fold quads and add crossings on Monaco, so
// the default is what removes them.
struct DemoRequests {
  nlohmann::json focus, mental, destination;
};

DemoRequests demo_requests(const std::string& network, const nlohmann::json& topology) {
  const auto& pos = topology["positions"];
  const auto& ids = topology["node_ids"];
  const std::size_t n = ids.size();
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (std::size_t i = 0; i < n; ++i) {
    x0 = std::min(x0, pos[2 * i].get<double>()), x1 = std::max(x1, pos[2 * i].get<double>());
    y0 = std::min(y0, pos[2 * i + 1].get<double>()), y1 = std::max(y1, pos[2 * i + 1].get<double>());
  }
  const double cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  const double mx = 111320 * std::cos(cy * M_PI / 180), my = 110540;  // metres per degree
  const double w = (x1 - x0) * mx, h = (y1 - y0) * my;
  auto xy = [&](std::size_t i) {
    return std::pair{(pos[2 * i].get<double>() - cx) * mx, (pos[2 * i + 1].get<double>() - cy) * my};
  };
  auto lonlat = [&](double x, double y) { return nlohmann::json::array({cx + x / mx, cy + y / my}); };
  std::vector<std::vector<std::pair<std::size_t, double>>> adj(n);
  for (const auto& way : topology["ways"]) {
    const auto& nodes = way["nodes"];
    for (std::size_t k = 1; k < nodes.size(); ++k) {
      auto a = nodes[k - 1].get<std::size_t>(), b = nodes[k].get<std::size_t>();
      auto [ax, ay] = xy(a);
      auto [bx, by] = xy(b);
      adj[a].push_back({b, std::hypot(ax - bx, ay - by)});
      adj[b].push_back({a, std::hypot(ax - bx, ay - by)});
    }
  }
  auto nearest = [&](double x, double y, const std::vector<double>* reachable) {
    std::size_t best = 0;
    double best_d = 1e300;
    for (std::size_t i = 0; i < n; ++i) {
      if (adj[i].empty() || (reachable && (*reachable)[i] >= 1e300)) continue;
      auto [px, py] = xy(i);
      double d = std::hypot(px - x, py - y);
      if (d < best_d) best_d = d, best = i;
    }
    return best;
  };
  const nlohmann::json common = {{"roads", network}, {"output", {{"roads", "none"}}}, {"check_crossings", true}};
  DemoRequests out;
  out.focus = common;
  out.focus["regions"] = {{{"center", {cx, cy}}, {"radius_m", std::min(w, h) / 10}, {"scale", 3}}};
  // 24 vertices near a circle (1.15 times its radius) pulled onto it.
  const double r = 0.2 * std::min(w, h);
  out.mental = common;
  out.mental["guides"] = nlohmann::json::array();
  std::vector<bool> used(n, false);
  for (int k = 0; k < 24; ++k) {
    const double a = 2 * M_PI * k / 24;
    auto i = nearest(1.15 * r * std::cos(a), 1.15 * r * std::sin(a), nullptr);
    if (used[i]) continue;
    used[i] = true;
    out.mental["guides"].push_back({{"vertex", ids[i]}, {"target", lonlat(r * std::cos(a), r * std::sin(a))}});
  }
  // The shortest route between points 30 % left and right of the centre, onto a straight line.
  const auto s = nearest(-0.3 * w, -0.1 * h, nullptr);
  std::vector<double> dist(n, 1e300);
  std::vector<std::size_t> prev(n, n);
  std::priority_queue<std::pair<double, std::size_t>, std::vector<std::pair<double, std::size_t>>, std::greater<>> queue;
  dist[s] = 0;
  queue.push({0, s});
  while (!queue.empty()) {
    auto [d, u] = queue.top();
    queue.pop();
    if (d > dist[u]) continue;
    for (auto [v, len] : adj[u])
      if (d + len < dist[v]) dist[v] = d + len, prev[v] = u, queue.push({dist[v], v});
  }
  const auto e = nearest(0.3 * w, 0.1 * h, &dist);
  std::vector<std::int64_t> route;
  for (auto v = e; v != n; v = prev[v]) route.insert(route.begin(), ids[v].get<std::int64_t>());
  auto [sx, sy] = xy(s);
  auto [ex, ey] = xy(e);
  out.destination = common;
  out.destination["route"] = route;
  out.destination["sketch"] = {lonlat(sx, sy), lonlat(ex, ey)};
  out.destination["simplify_m"] = 10;
  return out;
}

TEST_F(DeformApi, DemoRequestsFoldNothingAndAddNoCrossingByDefault) {
  std::size_t raw_folds = 0, raw_crossings = 0;
  for (const std::string network : {"west-oakland", "monaco"}) {
    const auto topo = live->get_json("/api/v1/roads/" + network + "?format=topology");
    const auto demo = demo_requests(network, topo);
    for (const auto& [app, body] : {std::pair{"focus", demo.focus}, {"mental", demo.mental}, {"destination", demo.destination}}) {
      const auto out = ok(app, body);
      EXPECT_EQ(out["stats"]["foldovers"], 0) << network << " " << app << ": " << out["stats"].dump();
      EXPECT_EQ(out["stats"]["crossings_added"], 0) << network << " " << app << ": " << out["stats"].dump();
      auto raw = body;
      raw["relax"] = false;
      const auto raw_out = ok(app, raw);
      raw_folds += raw_out["stats"]["foldovers"].get<std::size_t>();
      raw_crossings += raw_out["stats"]["crossings_added"].get<std::size_t>();
      EXPECT_EQ(raw_out["stats"]["relax_iterations"], 0);
      EXPECT_EQ(raw_out["stats"]["untangle_steps"], 0);
      // What the relaxation costs: the residue may grow, within reason.
      EXPECT_LT(out["stats"]["residue"].get<double>(), 3 * raw_out["stats"]["residue"].get<double>() + 1e-9)
          << network << " " << app;
    }
  }
  EXPECT_GT(raw_folds, 0u) << "the raw solves fold nothing: this test would not see a regression";
  EXPECT_GT(raw_crossings, 0u) << "the raw solves add no crossing: this test would not see a regression";
}

}  // namespace
}  // namespace tourmap::test
