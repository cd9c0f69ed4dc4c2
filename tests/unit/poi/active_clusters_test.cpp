#include "poi/active_clusters.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace tourmap::poi {
namespace {

std::vector<ClusterPoint> clustered_points(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 10000.0);
  std::normal_distribution<double> jitter(0.0, 150.0);
  std::lognormal_distribution<double> w(0.0, 1.5);
  std::vector<geo::XY> towns(30);
  for (auto& c : towns) c = {u(rng), u(rng)};
  std::vector<ClusterPoint> p(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = towns[i % towns.size()];
    p[i] = {{c.x + jitter(rng), c.y + jitter(rng)}, w(rng)};
  }
  return p;
}

bool is_ancestor(const ClusterTree& t, std::uint32_t a, std::uint32_t b) {
  for (std::int32_t at = t.nodes[b].parent; at >= 0; at = t.nodes[static_cast<std::uint32_t>(at)].parent)
    if (static_cast<std::uint32_t>(at) == a) return true;
  return false;
}

// The maximal active clusters by brute force: active, and the parent is not.
std::vector<std::uint32_t> brute_force(const ClusterTree& t, geo::XY lo, geo::XY hi) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t id = 0; id < t.nodes.size(); ++id) {
    const auto& c = t.nodes[id];
    if (is_active(c, lo, hi) && (c.parent < 0 || !is_active(t.nodes[static_cast<std::uint32_t>(c.parent)], lo, hi)))
      out.push_back(id);
  }
  return out;
}

TEST(PoiActiveClusters, RespectTheWindowAndRankByProminence) {
  auto points = clustered_points(2000, 4);
  ClusterOptions options;
  options.dense_limit = 200;
  auto t = build_cluster_tree(points, options);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1000.0, 11000.0), size(100.0, 12000.0);
  for (int q = 0; q < 300; ++q) {
    geo::XY lo{u(rng), u(rng)};
    geo::XY hi{lo.x + size(rng), lo.y + size(rng)};
    auto r = active_clusters(t, lo, hi, 10);
    auto expected = brute_force(t, lo, hi);
    ASSERT_EQ(r.active, expected.size());
    ASSERT_EQ(r.top.size(), std::min<std::size_t>(10, expected.size()));
    ASSERT_EQ(r.previews.size(), std::min<std::size_t>(20, expected.size()) - r.top.size());
    ASSERT_EQ(r.prominence.size(), r.top.size() + r.previews.size());

    std::vector<std::uint32_t> shown = r.top;
    shown.insert(shown.end(), r.previews.begin(), r.previews.end());
    double sum = 0;
    for (std::size_t i = 0; i < shown.size(); ++i) {
      const auto& c = t.nodes[shown[i]];
      EXPECT_GE(c.min.x, lo.x);
      EXPECT_GE(c.min.y, lo.y);
      EXPECT_LE(c.max.x, hi.x);
      EXPECT_LE(c.max.y, hi.y);
      EXPECT_LT(std::max(c.max.x - c.min.x, c.max.y - c.min.y), std::min(hi.x - lo.x, hi.y - lo.y));
      EXPECT_TRUE(std::binary_search(expected.begin(), expected.end(), shown[i]));
      for (std::size_t j = 0; j < shown.size(); ++j)
        if (i != j) {
          EXPECT_FALSE(is_ancestor(t, shown[i], shown[j]));
        }
      if (i > 0) {
        EXPECT_GE(r.prominence[i - 1], r.prominence[i]);
      }
      sum += r.prominence[i];
    }
    EXPECT_LE(sum, 1.0 + 1e-12);
    // Previews follow the top: nothing shown later outranks anything shown earlier, and nothing
    // left out outranks the last shown.
    if (!shown.empty()) {
      double last = t.nodes[shown.back()].worth;
      for (auto id : expected)
        if (std::find(shown.begin(), shown.end(), id) == shown.end()) {
          EXPECT_LE(t.nodes[id].worth, last);
        }
    }
    double total = 0;
    for (auto id : expected) total += t.nodes[id].worth;
    for (std::size_t i = 0; i < shown.size(); ++i) EXPECT_NEAR(r.prominence[i], t.nodes[shown[i]].worth / total, 1e-12);
  }
}

TEST(PoiActiveClusters, WholeExtentGivesTheBiggestClustersInside) {
  auto points = clustered_points(1000, 5);
  auto t = build_cluster_tree(points);
  const auto& root = t.nodes[t.root];
  geo::XY pad{1, 1};
  auto r = active_clusters(t, {root.min.x - pad.x, root.min.y - pad.y}, {root.max.x + pad.x, root.max.y + pad.y}, 3);
  EXPECT_EQ(r.active, brute_force(t, {root.min.x - 1, root.min.y - 1}, {root.max.x + 1, root.max.y + 1}).size());
  EXPECT_GE(r.active, 2u);  // the root itself is as big as the window
  EXPECT_EQ(r.top.size(), std::min<std::size_t>(3, r.active));
  // The top cluster carries the most worthy POI of all.
  EXPECT_EQ(t.nodes[r.top[0]].worth, root.worth);
  // A square window far bigger than the data holds just the root.
  double big = 1e7;
  auto all = active_clusters(t, {-big, -big}, {big, big}, 3);
  EXPECT_EQ(all.active, 1u);
  EXPECT_EQ(all.top, std::vector<std::uint32_t>{t.root});
  EXPECT_DOUBLE_EQ(all.prominence[0], 1.0);
}

TEST(PoiActiveClusters, EmptyAndDegenerate) {
  ClusterTree empty;
  EXPECT_EQ(active_clusters(empty, {0, 0}, {1, 1}, 10).active, 0u);
  auto t = build_cluster_tree({{{5, 5}, 0.0}, {{6, 5}, 0.0}});
  auto r = active_clusters(t, {0, 0}, {10, 10}, 10);
  ASSERT_EQ(r.top.size(), 1u);  // the pair: 1 wide in a 10 window
  EXPECT_EQ(r.top[0], t.root);
  EXPECT_DOUBLE_EQ(r.prominence[0], 1.0);
  auto split = active_clusters(t, {0, 0}, {5.5, 10}, 10);  // only the first POI is inside
  EXPECT_EQ(split.top, std::vector<std::uint32_t>{0});
  EXPECT_EQ(active_clusters(t, {20, 20}, {30, 30}, 10).active, 0u);  // nothing inside
  EXPECT_EQ(active_clusters(t, {10, 10}, {0, 0}, 10).active, 0u);    // inverted window
  // Zero worth everywhere: equal prominence.
  auto small = active_clusters(t, {0, 0}, {5.5, 5.5}, 0);
  EXPECT_EQ(small.active, 1u);
  EXPECT_TRUE(small.top.empty());
}

}  // namespace
TEST(PoiActiveClusters, RefinesAWholeMapWindowToAtLeastTheRequestedCount) {
  auto points = clustered_points(1000, 5);
  auto t = build_cluster_tree(points);
  const double big = 1e7;
  auto paper = active_clusters(t, {-big, -big}, {big, big}, 10);
  ASSERT_EQ(paper.active, 1u);
  auto refined = active_clusters(t, {-big, -big}, {big, big}, 10, 20);
  EXPECT_GE(refined.active, 20u);
  EXPECT_EQ(refined.top.size(), 10u);
  EXPECT_EQ(refined.previews.size(), 10u);
  // The most worthy POI stays on top.
  EXPECT_EQ(t.nodes[refined.top[0]].worth, t.nodes[t.root].worth);
  double sum = 0;
  for (double p : refined.prominence) sum += p;
  EXPECT_LE(sum, 1.0 + 1e-9);
  // A tree smaller than the requested count ends at single POIs.
  auto pair = build_cluster_tree({{{5, 5}, 1.0}, {{6, 5}, 2.0}});
  auto both = active_clusters(pair, {0, 0}, {10, 10}, 10, 20);
  EXPECT_EQ(both.active, 2u);
  EXPECT_EQ(both.top, (std::vector<std::uint32_t>{1, 0}));
  // A window's refined set covers exactly the POIs of the paper's set.
  auto window_paper = active_clusters(t, {-big, -big}, {big, big}, 1000);
  auto window_refined = active_clusters(t, {-big, -big}, {big, big}, 1000, 50);
  std::uint32_t covered_paper = 0, covered_refined = 0;
  for (auto id : window_paper.top) covered_paper += t.nodes[id].size;
  for (auto id : window_refined.top) covered_refined += t.nodes[id].size;
  EXPECT_EQ(covered_paper, covered_refined);
  EXPECT_EQ(covered_refined, 1000u);
}

}  // namespace tourmap::poi
