#include "poi/spatial.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace tourmap::poi {
namespace {

using geo::XY;

// Towns of 1..40 points (sigma 1..50) scattered over 100 km, some points stacked exactly, and a
// few far outliers: the kinds of input where a packed tree's boxes overlap and ties abound.
std::vector<XY> clustered_points(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1e5);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<XY> p;
  while (p.size() < n) {
    const XY c{u(rng), u(rng)};
    const double sigma = 1.0 + 49.0 * std::uniform_real_distribution<double>(0, 1)(rng);
    const std::size_t size = 1 + rng() % 40;
    for (std::size_t i = 0; i < size && p.size() < n; ++i) {
      if (i > 0 && rng() % 5 == 0)
        p.push_back(p.back());  // stacked on the previous one
      else
        p.push_back({c.x + sigma * normal(rng), c.y + sigma * normal(rng)});
    }
  }
  for (std::size_t i = 0; i < n / 100; ++i) p[rng() % n] = {u(rng) * 30, -u(rng) * 30};
  return p;
}

double d2(XY a, XY b) { return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y); }

// Every row holds k distinct other points whose distances are the k smallest (as a multiset).
void expect_exact_neighbours(const std::vector<XY>& p, const Neighbours& nb, std::size_t k) {
  ASSERT_EQ(nb.k, p.size() < 2 ? 0 : std::min(k, p.size() - 1));
  ASSERT_EQ(nb.index.size(), p.size() * nb.k);
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    std::vector<double> all, got;
    for (std::uint32_t j = 0; j < p.size(); ++j)
      if (j != i) all.push_back(d2(p[i], p[j]));
    std::sort(all.begin(), all.end());
    all.resize(nb.k);
    std::vector<std::uint32_t> row(nb.index.begin() + i * nb.k, nb.index.begin() + (i + 1) * nb.k);
    for (std::uint32_t j : row) {
      ASSERT_LT(j, p.size());
      ASSERT_NE(j, i);
      got.push_back(d2(p[i], p[j]));
    }
    EXPECT_TRUE(std::is_sorted(got.begin(), got.end())) << "point " << i << ": nearest first";
    std::sort(row.begin(), row.end());
    EXPECT_EQ(std::adjacent_find(row.begin(), row.end()), row.end()) << "point " << i << ": a neighbour twice";
    EXPECT_EQ(got, all) << "point " << i;
  }
}

TEST(PoiSpatial, NearestNeighboursEqualBruteForceInAnyOrder) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    auto p = clustered_points(1500, seed);
    for (std::size_t k : {1u, 8u, 15u, 16u, 40u}) expect_exact_neighbours(p, k_nearest(p, k), k);
    // In Hilbert order, as the cover uses them.
    std::vector<XY> sorted;
    for (std::uint32_t i : hilbert_order(p)) sorted.push_back(p[i]);
    expect_exact_neighbours(sorted, k_nearest(sorted, 8), 8);
  }
}

TEST(PoiSpatial, NearestNeighboursOnTwoThreadsEqualOneThread) {
  auto p = clustered_points(40000, 9);
  std::vector<XY> sorted;
  for (std::uint32_t i : hilbert_order(p)) sorted.push_back(p[i]);
  util::ForkJoin pool(2);
  Neighbours one, two;
  k_nearest(sorted, 8, one);
  k_nearest(sorted, 8, two, &pool);
  EXPECT_EQ(one.index, two.index);
  // Spot-check against brute force (the full check is quadratic).
  for (std::uint32_t i = 0; i < sorted.size(); i += 997) {
    std::vector<double> all;
    for (std::uint32_t j = 0; j < sorted.size(); ++j)
      if (j != i) all.push_back(d2(sorted[i], sorted[j]));
    std::nth_element(all.begin(), all.begin() + 7, all.end());
    EXPECT_EQ(d2(sorted[i], sorted[two.index[i * 8 + 7]]), all[7]) << "point " << i;
  }
}

TEST(PoiSpatial, NearestNeighboursOfTinyInputs) {
  EXPECT_EQ(k_nearest({}, 8).k, 0u);
  EXPECT_EQ(k_nearest({{1, 1}}, 8).k, 0u);
  for (std::size_t n : {2u, 3u, 17u, 33u}) {
    auto p = clustered_points(n, 3);
    expect_exact_neighbours(p, k_nearest(p, 8), 8);
    expect_exact_neighbours(p, k_nearest(p, 100), 100);
  }
  std::vector<XY> same(50, XY{3, 4});  // all tied at 0
  expect_exact_neighbours(same, k_nearest(same, 8), 8);
}

TEST(PoiSpatial, HilbertOrderIsAPermutationAlongTheCurve) {
  auto p = clustered_points(5000, 5);
  std::vector<std::uint32_t> cells;
  const auto order = hilbert_order(p, &cells);
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i);
  ASSERT_EQ(cells.size(), p.size());
  EXPECT_TRUE(std::is_sorted(cells.begin(), cells.end()));
  for (std::size_t r = 1; r < order.size(); ++r) {
    if (cells[r] == cells[r - 1]) {
      EXPECT_LT(order[r - 1], order[r]) << "one cell keeps the input order";
    }
  }
  // Neighbours along the curve are near on the map: on uniform points the mean step is a small
  // fraction of the mean step in a random order (about a third of the extent).
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1e5);
  std::vector<XY> uniform(5000);
  for (auto& q : uniform) q = {u(rng), u(rng)};
  auto mean_step = [&](const std::vector<std::uint32_t>& along) {
    double sum = 0;
    for (std::size_t r = 1; r < along.size(); ++r) sum += std::sqrt(d2(uniform[along[r]], uniform[along[r - 1]]));
    return sum / static_cast<double>(along.size() - 1);
  };
  std::vector<std::uint32_t> input(uniform.size());
  for (std::uint32_t i = 0; i < input.size(); ++i) input[i] = i;
  EXPECT_LT(mean_step(hilbert_order(uniform)), 0.05 * mean_step(input));
  // The 2 x 2 curve: (0,0) (0,1) (1,1) (1,0) in the classic orientation.
  EXPECT_EQ(hilbert_order({{1, 0}, {1, 1}, {0, 1}, {0, 0}}), (std::vector<std::uint32_t>{3, 2, 1, 0}));
  EXPECT_TRUE(hilbert_order({}).empty());
}

}  // namespace
}  // namespace tourmap::poi
