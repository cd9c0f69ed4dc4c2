// POI writes and cluster trees (issue 19): after a re-import that changes a few POIs, the next
// clusters request updates the tree served for the city's previous version instead of building
// one; a re-import that changes most POIs builds.

#include "live_server.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace tourmap::test {
namespace {

// n sights on a grid of 10 columns from (lon0, lat0), 0.007 deg apart east, 0.005 north.
std::string sights_csv(int n, const char* prefix, double lon0 = 16.30, double lat0 = 48.18) {
  std::string csv = "name,lon,lat\n";
  char line[96];
  for (int i = 0; i < n; ++i) {
    std::snprintf(line, sizeof line, "%s %d,%.5f,%.5f\n", prefix, i, lon0 + 0.007 * (i % 10), lat0 + 0.005 * (i / 10));
    csv += line;
  }
  return csv;
}

void import_pois(LiveServer& live, const std::string& name, const std::string& csv) {
  const auto r = run_command({kTourmapBin, "import", "pois", live.dir.write(name, csv), "--city", "vienna", "--db", live.db()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
}

// The names of the clusters' representatives (shown and previews) in a window.
std::vector<std::string> representatives(const LiveServer& live, const std::string& bbox) {
  const auto j = live.get_json("/api/v1/cities/vienna/clusters?m=3&bbox=" + bbox);
  std::vector<std::string> names;
  for (const char* list : {"clusters", "previews"})
    for (const auto& c : j[list]) names.push_back(c["representative"]["name"]);
  return names;
}

TEST(ClusterTreeReuseApi, APoiWriteUpdatesThePreviousTreeAndAWholeNewSetBuilds) {
  LiveServer live;
  import_pois(live, "a.csv", sights_csv(60, "Sight"));
  const double built = metric(live, "tourmap_cluster_trees_built");
  ASSERT_GE(built, 0);
  EXPECT_EQ(metric(live, "tourmap_cluster_trees_updated"), 0);
  const std::string around_59 = "16.3605,48.2025,16.3655,48.2075";  // Sight 59 alone
  EXPECT_EQ(representatives(live, around_59), std::vector<std::string>{"Sight 59"});
  EXPECT_EQ(metric(live, "tourmap_cluster_trees_built"), built + 1);

  // One sight fewer, and one more far from the grid: an update of the tree above.
  std::string csv = sights_csv(60, "Sight");
  csv.erase(csv.find("Sight 59,"));
  csv += "Prater Riesenrad,16.39570,48.21660\n";
  import_pois(live, "b.csv", csv);
  EXPECT_EQ(representatives(live, "16.390,48.213,16.400,48.220"), std::vector<std::string>{"Prater Riesenrad"});
  EXPECT_EQ(metric(live, "tourmap_cluster_trees_updated"), 1);
  EXPECT_EQ(metric(live, "tourmap_cluster_trees_built"), built + 1);
  EXPECT_TRUE(representatives(live, around_59).empty());
  EXPECT_EQ(representatives(live, "16.3535,48.2025,16.3585,48.2075"), std::vector<std::string>{"Sight 58"});
  const auto all = live.get_json("/api/v1/cities/vienna/clusters?m=5");
  EXPECT_GE(all["active"].get<int>(), 10);  // refined to at least 2m as before

  // A different set altogether: built from scratch.
  import_pois(live, "c.csv", sights_csv(60, "Elsewhere", 16.25, 48.15));
  EXPECT_GE(live.get_json("/api/v1/cities/vienna/clusters?m=5")["active"].get<int>(), 10);
  EXPECT_EQ(metric(live, "tourmap_cluster_trees_built"), built + 2);
  EXPECT_EQ(metric(live, "tourmap_cluster_trees_updated"), 1);
}

}  // namespace
}  // namespace tourmap::test
