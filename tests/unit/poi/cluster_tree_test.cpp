#include "poi/cluster_tree.hpp"

#include "cluster_tree_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace tourmap::poi {
namespace {

std::vector<ClusterPoint> random_points(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 10000.0);
  std::exponential_distribution<double> w(1.0);
  std::vector<ClusterPoint> p(n);
  for (auto& q : p) q = {{u(rng), u(rng)}, std::floor(w(rng) * 4)};  // integral worth: many ties
  return p;
}

TEST(PoiClusterTree, DenseTreeIsConsistent) {
  auto points = random_points(120, 1);
  auto t = build_cluster_tree(points);
  expect_consistent(t, points);
  // Cycle covers merge at least pairs: about log2(120) levels at most.
  EXPECT_LE(t.nodes[t.root].level, 7u);
}

TEST(PoiClusterTree, SparseRoundsAreConsistent) {
  auto points = random_points(3000, 2);
  ClusterOptions options;
  options.dense_limit = 100;
  auto t = build_cluster_tree(points, options);
  expect_consistent(t, points);
  EXPECT_LE(t.nodes[t.root].level, 20u);
}

TEST(PoiClusterTree, SeparatedPairsMergeFirst) {
  std::vector<ClusterPoint> points = {{{0, 0}, 1}, {{1000, 0}, 2}, {{0, 1000}, 3},
                                      {{1, 0}, 4}, {{1000, 1}, 5}, {{1, 1000}, 6}};
  for (std::size_t dense_limit : {600, 2}) {
    ClusterOptions options;
    options.dense_limit = dense_limit;
    options.k = 3;
    auto t = build_cluster_tree(points, options);
    expect_consistent(t, points);
    for (std::uint32_t i = 0; i < 3; ++i) {
      ASSERT_EQ(t.nodes[i].parent, t.nodes[i + 3].parent);
      const auto& pair = t.nodes[static_cast<std::uint32_t>(t.nodes[i].parent)];
      EXPECT_EQ(pair.size, 2u);
      EXPECT_EQ(pair.level, 1u);
      EXPECT_EQ(pair.representative, i + 3);
    }
  }
}

TEST(PoiClusterTree, DegenerateInputs) {
  for (std::size_t n : {0, 1, 2, 3}) {
    auto points = random_points(n, 3);
    auto t = build_cluster_tree(points);
    expect_consistent(t, points);
    EXPECT_EQ(t.nodes.size(), n == 0 ? 0 : n == 1 ? 1 : n + 1);
  }
  for (std::size_t dense_limit : {600, 10}) {
    std::vector<ClusterPoint> same(200, {{3, 4}, 1.0});
    ClusterOptions options;
    options.dense_limit = dense_limit;
    auto t = build_cluster_tree(same, options);
    expect_consistent(t, same);
    EXPECT_EQ(t.nodes[t.root].representative, 0u);
    EXPECT_EQ(t.nodes[t.root].max.x - t.nodes[t.root].min.x, 0.0);
  }
  // Two far-apart piles of duplicates plus a few loners.
  std::vector<ClusterPoint> piles(500, {{0, 0}, 1.0});
  piles.resize(1000, {{1e6, 1e6}, 2.0});
  piles.push_back({{5e5, 0}, 0.5});
  piles.push_back({{5e5, 1}, 0.5});
  ClusterOptions options;
  options.dense_limit = 4;
  auto t = build_cluster_tree(piles, options);
  expect_consistent(t, piles);
  EXPECT_EQ(t.nodes[t.root].representative, 500u);
}

TEST(PoiClusterTree, RejectsBadPoints) {
  EXPECT_THROW(build_cluster_tree({{{0, 0}, 1}, {{NAN, 0}, 1}}), std::invalid_argument);
  EXPECT_THROW(build_cluster_tree({{{0, INFINITY}, 1}}), std::invalid_argument);
  EXPECT_THROW(build_cluster_tree({{{0, 0}, -1}}), std::invalid_argument);
  EXPECT_THROW(build_cluster_tree({{{0, 0}, NAN}}), std::invalid_argument);
}

}  // namespace
}  // namespace tourmap::poi
