// Interests (issue 17, part 3; beyond the paper: its future work 6.2) against a real server:
// per-category weights on GET/POST .../layout, .../clusters and .../visual-worth change the
// visual worth, the layout's edge lengths and the active clusters; equivalent weights (another
// order, scaled, all ones) give the same bytes as each other (all ones: as no interests); bad
// ones are refused naming `interests`; GET /cities/{id} lists the categories with counts.
// Monaco (from its OSM extract): 13 POIs in 5 categories, 70 bus edges.

#include "live_server_suite.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace tourmap::test {
namespace {

class MonacoServer {
 public:
  explicit MonacoServer(const std::vector<std::string>& extra_flags) {
    dir.write("web/index.html", "<!doctype html><title>tourmap</title>");
    const auto manifest = dir.write("manifest.json", R"({"cities":[
      {"id":"monaco","name":"Monaco","source":{"osm":"roads/monaco.osm.gz","attribution":"OSM"}}]})");
    const auto db = dir.file("t.db");
    auto imported = run_command({kTourmapBin, "import", "manifest", manifest, "--data-dir", data_dir(), "--db", db});
    if (imported.exit_code != 0) throw std::runtime_error("import failed: " + imported.output);
    std::vector<std::string> flags = {"--web-root", dir.file("web"), "--access-log", "off"};
    flags.insert(flags.end(), extra_flags.begin(), extra_flags.end());
    server = std::make_unique<ServerProcess>(kTourmapBin, db, flags);
  }
  HttpResult get(const std::string& target) const { return http_get(server->port(), target); }
  HttpResult post(const std::string& target, const nlohmann::json& body) const {
    return http_request(server->port(), "POST", target, {{"Content-Type", "application/json"}}, body.dump());
  }
  nlohmann::json get_json(const std::string& target) const {
    auto r = get(target);
    if (r.status != 200) throw std::runtime_error(target + " -> " + std::to_string(r.status) + " " + r.body);
    return nlohmann::json::parse(r.body);
  }

  TempDir dir;
  std::unique_ptr<ServerProcess> server;
};

const std::string kLayout = "/api/v1/cities/monaco/layout";
const std::string kClusters = "/api/v1/cities/monaco/clusters";

class Interests : public ::testing::Test {
 protected:
  // No background improvement: default answers stay as first served.
  static void SetUpTestSuite() { monaco = new MonacoServer({"--improve-mip", "0"}); }
  static void TearDownTestSuite() {
    delete monaco;
    monaco = nullptr;
  }
  static inline MonacoServer* monaco = nullptr;
};

// The edges' visual-worth lengths (eq. 5.4) of a layout answer.
std::vector<double> min_lengths(const nlohmann::json& layout) {
  std::vector<double> out;
  for (const auto& e : layout["edges"]["features"]) out.push_back(e["properties"]["min_length"].get<double>());
  return out;
}

// Every shown cluster's representative category.
std::multiset<std::string> shown_categories(const nlohmann::json& clusters) {
  std::multiset<std::string> out;
  for (const char* part : {"clusters", "previews"})
    for (const auto& c : clusters[part]) out.insert(c["representative"]["category"].get<std::string>());
  return out;
}

TEST_F(Interests, CitySummaryListsCategoriesWithCounts) {
  const auto city = monaco->get_json("/api/v1/cities/monaco");
  ASSERT_TRUE(city["categories"].is_array()) << city.dump();
  std::map<std::string, int> counts;
  int total = 0;
  for (const auto& c : city["categories"]) {
    counts[c["id"].get<std::string>()] = c["count"].get<int>();
    total += c["count"].get<int>();
  }
  EXPECT_EQ(counts, (std::map<std::string, int>{{"attraction", 5}, {"castle", 1}, {"museum", 5}, {"viewpoint", 1}, {"zoo", 1}}));
  EXPECT_EQ(total, monaco->get_json("/api/v1/cities/monaco/pois")["matched"].get<int>());
}

TEST_F(Interests, LayoutFollowsTheWeightsAndEquivalentWeightsShareTheAnswer) {
  const auto plain = monaco->get(kLayout);
  ASSERT_EQ(plain.status, 200) << plain.body;
  // All ones is the paper's worth: the same bytes, from the same cache entry.
  const auto ones = monaco->get(kLayout + "?interests=zoo:1,museum:1,attraction:1,castle:1,viewpoint:1");
  ASSERT_EQ(ones.status, 200) << ones.body;
  EXPECT_EQ(ones.body, plain.body);
  EXPECT_EQ(ones.header("x-result-cache"), "hit");
  EXPECT_FALSE(nlohmann::json::parse(plain.body)["params"].contains("interests"));

  // Museums ten times the rest: another layout.
  const auto museums = monaco->get(kLayout + "?interests=museum:10");
  ASSERT_EQ(museums.status, 200) << museums.body;
  const auto a = nlohmann::json::parse(plain.body), b = nlohmann::json::parse(museums.body);
  EXPECT_EQ(b["params"]["interests"],
            (nlohmann::json{{"attraction", 0.1}, {"castle", 0.1}, {"viewpoint", 0.1}, {"zoo", 0.1}}));
  EXPECT_NE(min_lengths(a), min_lengths(b));
  EXPECT_NE(a["stations"], b["stations"]);
  EXPECT_EQ(b["solver"]["improvement"], "none");

  // The same weights scaled and in another order, by GET and POST: the same bytes.
  const auto scaled = monaco->get(kLayout + "?interests=viewpoint:0.5,museum:5,zoo:0.5,castle:0.5,attraction:0.5");
  ASSERT_EQ(scaled.status, 200) << scaled.body;
  EXPECT_EQ(scaled.body, museums.body);
  EXPECT_EQ(scaled.header("x-result-cache"), "hit");
  const auto posted = monaco->post(kLayout, {{"interests", {{"museum", 1}, {"zoo", 0.1}, {"castle", 0.1},
                                                            {"attraction", 0.1}, {"viewpoint", 0.1}}}});
  ASSERT_EQ(posted.status, 200) << posted.body;
  EXPECT_EQ(posted.body, museums.body);

  // Museums left out of the worth: a third layout.
  const auto without = monaco->get(kLayout + "?interests=museum:0");
  ASSERT_EQ(without.status, 200) << without.body;
  const auto c = nlohmann::json::parse(without.body);
  EXPECT_NE(min_lengths(c), min_lengths(a));
  EXPECT_NE(min_lengths(c), min_lengths(b));
  // The layout still places every POI (clients may filter); only the worth changed.
  EXPECT_EQ(c["pois"]["features"].size(), a["pois"]["features"].size());
}

TEST_F(Interests, GeographicClustersFollowTheWeights) {
  const auto plain = monaco->get(kClusters + "?m=3");
  ASSERT_EQ(plain.status, 200) << plain.body;
  const auto ones = monaco->get(kClusters + "?m=3&interests=attraction:2,castle:2,museum:2,viewpoint:2,zoo:2");
  EXPECT_EQ(ones.body, plain.body);

  const auto museums = monaco->get(kClusters + "?m=3&interests=museum:10");
  ASSERT_EQ(museums.status, 200) << museums.body;
  EXPECT_NE(museums.body, plain.body);
  const auto top = nlohmann::json::parse(museums.body)["clusters"];
  ASSERT_FALSE(top.empty());
  EXPECT_EQ(top[0]["representative"]["category"], "museum") << museums.body;
  EXPECT_NE(nlohmann::json::parse(plain.body)["clusters"][0]["representative"]["category"], "museum") << plain.body;
  const auto scaled = monaco->get(kClusters + "?m=3&interests=zoo:0.1,attraction:0.1,viewpoint:0.1,castle:0.1,museum:1");
  EXPECT_EQ(scaled.body, museums.body);

  // Weight 0: no museum is shown, and the clusters hold 5 POIs fewer (the 5 museums). (A
  // whole-city window leaves out a POI on its edge either way: 12 of 13 without interests.)
  const auto without = monaco->get(kClusters + "?m=10&interests=museum:0");
  ASSERT_EQ(without.status, 200) << without.body;
  const auto all = nlohmann::json::parse(monaco->get(kClusters + "?m=10").body);
  const auto w = nlohmann::json::parse(without.body);
  EXPECT_EQ(shown_categories(w).count("museum"), 0u) << without.body;
  EXPECT_GT(shown_categories(all).count("museum"), 0u) << all.dump();
  auto size = [](const nlohmann::json& answer) {
    int n = 0;
    for (const char* part : {"clusters", "previews"})
      for (const auto& c : answer[part]) n += c["size"].get<int>();
    return n;
  };
  EXPECT_EQ(size(w), size(all) - 5) << without.body;
}

TEST_F(Interests, LayoutClustersFollowTheWeights) {
  const std::string window = "?space=layout&m=3&bbox=-100000,-100000,100000,100000";
  const auto plain = monaco->get(kClusters + window);
  ASSERT_EQ(plain.status, 200) << plain.body;
  EXPECT_EQ(monaco->get(kClusters + window + "&interests=museum:1,zoo:1").body, plain.body);
  const auto museums = monaco->get(kClusters + window + "&interests=museum:10");
  ASSERT_EQ(museums.status, 200) << museums.body;
  EXPECT_NE(museums.body, plain.body);
  EXPECT_EQ(nlohmann::json::parse(museums.body)["clusters"][0]["representative"]["category"], "museum") << museums.body;
  EXPECT_EQ(monaco->get(kClusters + window + "&interests=attraction:0.2,castle:0.2,museum:2,viewpoint:0.2,zoo:0.2").body,
            museums.body);
  const auto without = monaco->get(kClusters + window + "&interests=museum:0");
  ASSERT_EQ(without.status, 200) << without.body;
  EXPECT_EQ(shown_categories(nlohmann::json::parse(without.body)).count("museum"), 0u) << without.body;
}

TEST_F(Interests, VisualWorthFollowsTheWeights) {
  const std::string raster = "/api/v1/cities/monaco/visual-worth?width=16&height=16";
  const auto plain = monaco->get(raster);
  ASSERT_EQ(plain.status, 200) << plain.body;
  EXPECT_EQ(monaco->get(raster + "&interests=castle:3,museum:3,zoo:3,attraction:3,viewpoint:3").body, plain.body);
  const auto museums = monaco->get(raster + "&interests=museum:10");
  ASSERT_EQ(museums.status, 200) << museums.body;
  EXPECT_NE(nlohmann::json::parse(museums.body)["values"], nlohmann::json::parse(plain.body)["values"]);
}

TEST_F(Interests, BadInterestsAreRefusedNamingTheField) {
  const std::string too_many = [] {
    std::string s;
    for (int i = 0; i < 65; ++i) s += (i ? ",c" : "c") + std::to_string(i) + ":1";
    return s;
  }();
  for (const std::string& q : {std::string("musem:1"), std::string("museum:-1"), std::string("museum:nan"),
                               std::string("museum:11"), std::string("museum"), std::string("museum:"),
                               std::string("museum:1,museum:2"), std::string(65, 'a') + ":1", too_many,
                               std::string("attraction:0,castle:0,museum:0,viewpoint:0,zoo:0")}) {
    SCOPED_TRACE(q);
    expect_error(monaco->get(kLayout + "?interests=" + q), 400, "interests");
    expect_error(monaco->get(kClusters + "?interests=" + q), 400, "interests");
    expect_error(monaco->get(kClusters + "?space=layout&bbox=0,0,1,1&interests=" + q), 400, "interests");
    expect_error(monaco->get("/api/v1/cities/monaco/visual-worth?interests=" + q), 400, "interests");
  }
  // An unknown category: the message lists the city's.
  const auto unknown = monaco->get(kLayout + "?interests=musem:1");
  EXPECT_NE(error_of(unknown)["message"].get<std::string>().find("'attraction', 'castle', 'museum', 'viewpoint', 'zoo'"),
            std::string::npos)
      << unknown.body;
  for (const auto& body : {nlohmann::json{{"interests", {{"museum", "high"}}}}, nlohmann::json{{"interests", {1, 2}}},
                           nlohmann::json{{"interests", {{"museum", 10.5}}}}, nlohmann::json{{"interests", {{"musem", 1}}}}}) {
    SCOPED_TRACE(body.dump());
    expect_error(monaco->post(kLayout, body), 400, "interests");
  }
}

// With background improvements on: the default layout's is scheduled; layouts for interests
// are not improved and say so.
TEST(InterestsImprovement, OnlyTheDefaultLayoutIsImproved) {
  MonacoServer server({"--improve-mip", "0.5"});
  const auto plain = server.get_json(kLayout);
  EXPECT_EQ(plain["solver"]["improvement"], "scheduled") << plain["solver"].dump();
  const auto museums = server.get_json(kLayout + "?interests=museum:10");
  EXPECT_EQ(museums["solver"]["improvement"], "none") << museums["solver"].dump();
}

}  // namespace
}  // namespace tourmap::test
