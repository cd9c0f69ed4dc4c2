#include "api/cluster_tree_reuse.hpp"

#include "poi/serialize.hpp"

#include <gtest/gtest.h>

#include <random>

namespace tourmap::api {
namespace {

std::vector<poi::ClusterPoint> grid(std::size_t n) {
  std::vector<poi::ClusterPoint> p;
  for (std::size_t i = 0; i < n; ++i)
    p.push_back({{100.0 * static_cast<double>(i % 20) + (i % 7), 80.0 * static_cast<double>(i / 20)}, 1.0 + i % 5});
  return p;
}

// The leaves are the caller's POIs in the caller's order, whatever the update did inside.
void expect_leaves_are(const poi::ClusterTree& t, const std::vector<poi::ClusterPoint>& points) {
  ASSERT_EQ(t.leaves, points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(t.nodes[i].center.x, points[i].pos.x) << i;
    EXPECT_EQ(t.nodes[i].center.y, points[i].pos.y) << i;
    EXPECT_EQ(t.nodes[i].worth, points[i].worth) << i;
  }
  EXPECT_NO_THROW(poi::deserialize(poi::serialize(t)));
}

TEST(ClusterTreeReuse, FamilyDropsTheVersionOnly) {
  EXPECT_EQ(tree_family("clusters:geo:vienna@17:museums=2"), "clusters:geo:vienna@:museums=2");
  EXPECT_EQ(tree_family("clusters:layout:li@3:solver=fast:improved"), "clusters:layout:li@:solver=fast:improved");
  EXPECT_EQ(tree_family("clusters:geo:vienna@"), "clusters:geo:vienna@");
  EXPECT_EQ(tree_family("no version"), "no version");
}

TEST(ClusterTreeReuse, DerivedTreeFollowsTheNewOrder) {
  const auto before = grid(400);
  const poi::ClusterTree tree = poi::build_cluster_tree(before);
  // The new list: shuffled, 5 removed, 2 re-weighted, 3 added in the middle.
  auto after = before;
  after.erase(after.begin() + 10, after.begin() + 15);
  after[20].worth = 9;
  after[30].worth = 0;
  after.insert(after.begin() + 50, {{{5000, 5000}, 3}, {{-300, 20}, 1}, {{150, 170}, 2}});
  std::shuffle(after.begin(), after.end(), std::mt19937(2));
  poi::ClusterUpdateStats stats;
  const auto derived = derive_tree(tree, after, &stats);
  ASSERT_TRUE(derived);
  EXPECT_FALSE(stats.rebuilt);
  EXPECT_EQ(stats.inserted, 3u);
  expect_leaves_are(*derived, after);
}

TEST(ClusterTreeReuse, ManyMovesAreLeftToARebuild) {
  const auto before = grid(400);
  const poi::ClusterTree tree = poi::build_cluster_tree(before);
  auto after = before;
  for (std::size_t i = 0; i < 101; ++i) after[i].pos.x += 1;  // > a quarter moved: 101 removed, 101 added
  EXPECT_FALSE(derive_tree(tree, after));
  after = before;
  for (std::size_t i = 0; i < 15; ++i) after[i].pos.x += 1;  // few: derived
  const auto derived = derive_tree(tree, after);
  ASSERT_TRUE(derived);
  expect_leaves_are(*derived, after);
  // Stacked POIs pair up one by one.
  auto stacked = before;
  stacked.push_back(before[7]);
  stacked.push_back(before[7]);
  const auto with_copies = derive_tree(tree, stacked);
  ASSERT_TRUE(with_copies);
  expect_leaves_are(*with_copies, stacked);
}

TEST(ClusterTreeReuse, LatestTreesRememberWeaklyPerFamily) {
  LatestTrees latest;
  auto a = std::make_shared<const poi::ClusterTree>(poi::build_cluster_tree(grid(10)));
  latest.remember("clusters:geo:x@1", a);
  EXPECT_EQ(latest.previous("clusters:geo:x@1"), nullptr) << "the same version is not a previous one";
  EXPECT_EQ(latest.previous("clusters:geo:x@2"), a);
  EXPECT_EQ(latest.previous("clusters:geo:y@2"), nullptr);
  a.reset();
  EXPECT_EQ(latest.previous("clusters:geo:x@2"), nullptr) << "held weakly: gone with the cache's copy";
}

}  // namespace
}  // namespace tourmap::api
