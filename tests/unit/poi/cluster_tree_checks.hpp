#pragma once
// Checks shared by the cluster tree's tests (building and incremental updates).

#include "poi/cluster_tree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace tourmap::poi {

// Everything a consumer relies on: one root, every POI a leaf exactly once, fields consistent
// bottom-up.
inline void expect_consistent(const ClusterTree& t, const std::vector<ClusterPoint>& points) {
  const std::size_t n = points.size();
  ASSERT_EQ(t.leaves, n);
  if (n == 0) {
    EXPECT_TRUE(t.nodes.empty());
    return;
  }
  ASSERT_LT(t.root, t.nodes.size());
  EXPECT_EQ(t.nodes[t.root].parent, -1);
  EXPECT_EQ(t.nodes[t.root].size, n);
  EXPECT_EQ(t.children.size(), t.nodes.size() - 1);
  std::vector<int> listed(t.nodes.size(), 0);
  for (std::uint32_t id = 0; id < t.nodes.size(); ++id) {
    const ClusterNode& c = t.nodes[id];
    if (id != t.root) {
      ASSERT_GE(c.parent, 0) << id;
    }
    if (id < n) {
      EXPECT_EQ(c.child_count, 0u);
      EXPECT_EQ(c.size, 1u);
      EXPECT_EQ(c.level, 0u);
      EXPECT_EQ(c.representative, id);
      EXPECT_EQ(c.worth, points[id].worth);
      EXPECT_EQ(c.min.x, points[id].pos.x);
      EXPECT_EQ(c.max.y, points[id].pos.y);
      continue;
    }
    ASSERT_GE(c.child_count, 2u) << id;
    std::uint32_t size = 0;
    double worth = -1, cx = 0, cy = 0;
    std::uint32_t rep = 0;
    geo::XY lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
    for (std::uint32_t a = 0; a < c.child_count; ++a) {
      std::uint32_t ch = t.children[c.first_child + a];
      const ClusterNode& k = t.nodes[ch];
      ++listed[ch];
      EXPECT_EQ(k.parent, static_cast<std::int32_t>(id));
      EXPECT_LT(k.level, c.level);
      size += k.size;
      cx += k.center.x * k.size;
      cy += k.center.y * k.size;
      lo = {std::min(lo.x, k.min.x), std::min(lo.y, k.min.y)};
      hi = {std::max(hi.x, k.max.x), std::max(hi.y, k.max.y)};
      if (k.worth > worth || (k.worth == worth && k.representative < rep)) {
        worth = k.worth;
        rep = k.representative;
      }
    }
    EXPECT_EQ(c.size, size);
    EXPECT_EQ(c.worth, worth);
    EXPECT_EQ(c.representative, rep);
    EXPECT_EQ(points[c.representative].worth, c.worth);
    EXPECT_EQ(c.min.x, lo.x);
    EXPECT_EQ(c.min.y, lo.y);
    EXPECT_EQ(c.max.x, hi.x);
    EXPECT_EQ(c.max.y, hi.y);
    EXPECT_NEAR(c.center.x, cx / size, 1e-6);
    EXPECT_NEAR(c.center.y, cy / size, 1e-6);
  }
  for (std::uint32_t id = 0; id < t.nodes.size(); ++id) EXPECT_EQ(listed[id], id == t.root ? 0 : 1) << id;
  // Every POI reaches the root.
  for (std::uint32_t leaf = 0; leaf < n; ++leaf) {
    std::uint32_t at = leaf;
    for (std::size_t steps = 0; t.nodes[at].parent >= 0 && steps < t.nodes.size(); ++steps)
      at = static_cast<std::uint32_t>(t.nodes[at].parent);
    EXPECT_EQ(at, t.root);
  }
}


// Quality of a hierarchy: cut it into about `clusters` clusters (from the root, undo the merges
// of the highest round first, later nodes first within a round) and return the mean distance
// from each POI to the centroid of its cluster's POIs.
inline double mean_distance_to_centroid(const ClusterTree& t, std::size_t clusters) {
  std::vector<std::uint32_t> inner;
  for (std::uint32_t id = static_cast<std::uint32_t>(t.leaves); id < t.nodes.size(); ++id) inner.push_back(id);
  std::sort(inner.begin(), inner.end(), [&](std::uint32_t a, std::uint32_t b) {
    return t.nodes[a].level != t.nodes[b].level ? t.nodes[a].level > t.nodes[b].level : a > b;
  });
  std::vector<char> open(t.nodes.size(), 0);  // undone: its children are clusters of the cut
  std::size_t count = 1;
  for (std::uint32_t id : inner) {
    if (count >= clusters) break;
    open[id] = 1;
    count += t.nodes[id].child_count - 1;
  }
  double sum = 0;
  for (std::uint32_t leaf = 0; leaf < t.leaves; ++leaf) {
    std::uint32_t at = leaf;  // climb to the highest ancestor whose parent is undone (or the root)
    std::uint32_t cut = leaf;
    for (;;) {
      const std::int32_t p = t.nodes[at].parent;
      if (p < 0) {
        if (!open[at]) cut = at;
        break;
      }
      if (!open[p]) cut = static_cast<std::uint32_t>(p);
      at = static_cast<std::uint32_t>(p);
    }
    const geo::XY c = t.nodes[cut].center, q = t.nodes[leaf].center;
    sum += std::hypot(c.x - q.x, c.y - q.y);
  }
  return sum / static_cast<double>(std::max<std::size_t>(t.leaves, 1));
}

}  // namespace tourmap::poi
