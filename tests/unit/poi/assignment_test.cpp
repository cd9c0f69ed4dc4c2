#include "poi/assignment.hpp"
#include "poi/spatial.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace tourmap::poi {
namespace {

using geo::XY;

std::vector<XY> random_points(std::size_t n, unsigned seed, double extent = 1000.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, extent);
  std::vector<XY> p(n);
  for (auto& q : p) q = {u(rng), u(rng)};
  return p;
}

double dist(XY a, XY b) { return std::hypot(a.x - b.x, a.y - b.y); }

void expect_permutation(const std::vector<std::uint32_t>& s) {
  std::vector<char> hit(s.size(), 0);
  for (auto j : s) {
    ASSERT_LT(j, s.size());
    ASSERT_FALSE(hit[j]) << "successor " << j << " used twice";
    hit[j] = 1;
  }
}

// Brute force over all permutations without fixed points (n <= 7).
double brute_force(const std::vector<XY>& p) {
  std::vector<std::uint32_t> perm(p.size());
  for (std::uint32_t i = 0; i < p.size(); ++i) perm[i] = i;
  double best = INFINITY;
  do {
    bool ok = true;
    double c = 0;
    for (std::uint32_t i = 0; i < p.size() && ok; ++i) {
      ok = perm[i] != i;
      c += dist(p[i], p[perm[i]]);
    }
    if (ok) best = std::min(best, c);
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

TEST(PoiAssignment, DenseMatchesBruteForce) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    auto p = random_points(2 + seed % 6, seed);
    auto cover = min_cycle_cover_dense(p);
    expect_permutation(cover.successor);
    double c = 0;
    for (std::uint32_t i = 0; i < p.size(); ++i) {
      EXPECT_NE(cover.successor[i], i);
      c += dist(p[i], p[cover.successor[i]]);
    }
    EXPECT_NEAR(c, cover.cost, 1e-9 * c);
    EXPECT_NEAR(cover.cost, brute_force(p), 1e-9 * c) << "seed " << seed;
  }
}

TEST(PoiAssignment, SparseWithAllCandidatesMatchesDense) {
  for (unsigned seed = 1; seed <= 30; ++seed) {
    std::size_t n = 2 + (seed * 7) % 60;
    auto p = random_points(n, seed);
    if (seed % 5 == 0) p[1] = p[0];  // a duplicate now and then
    auto dense = min_cycle_cover_dense(p);
    auto sparse = min_cycle_cover_sparse(p, n - 1);
    expect_permutation(sparse.successor);
    EXPECT_EQ(sparse.self_loops, 0u) << "seed " << seed;
    EXPECT_NEAR(sparse.cost, dense.cost, 1e-6 * dense.cost) << "n " << n << " seed " << seed;
  }
}

// Tight towns with stacked points and long gaps between them: ties everywhere for the row
// reduction, and augmenting paths that shift whole chains.
TEST(PoiAssignment, SparseWithAllCandidatesMatchesDenseOnTownsWithStackedPoints) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1e4);
    std::vector<XY> p;
    while (p.size() < 240) {
      const XY c{u(rng), u(rng)};
      for (std::size_t i = 0, size = 1 + rng() % 9; i < size; ++i)
        p.push_back(rng() % 3 == 0 && i > 0 ? p.back() : XY{c.x + u(rng) / 1000, c.y + u(rng) / 1000});
    }
    auto dense = min_cycle_cover_dense(p);
    auto sparse = min_cycle_cover_sparse(p, p.size() - 1);
    expect_permutation(sparse.successor);
    EXPECT_EQ(sparse.self_loops, 0u);
    EXPECT_NEAR(sparse.cost, dense.cost, 1e-6 * dense.cost) << "seed " << seed;
  }
}

TEST(PoiAssignment, SparseWithFewCandidatesIsValidAndNotBetterThanDense) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    auto p = random_points(300, seed);
    auto dense = min_cycle_cover_dense(p);
    auto sparse = min_cycle_cover_sparse(p, 8);
    expect_permutation(sparse.successor);
    double distances = 0;
    for (std::uint32_t i = 0; i < p.size(); ++i) distances += dist(p[i], p[sparse.successor[i]]);
    EXPECT_LE(distances, sparse.cost + 1e-9);
    EXPECT_GE(sparse.cost, dense.cost * (1 - 1e-9));
    EXPECT_LE(sparse.cost, dense.cost * 1.05) << "kNN restriction should cost little on uniform points";
  }
}

TEST(PoiAssignment, SparseCostDoesNotDependOnInputOrder) {
  auto p = random_points(2000, 5);
  for (std::size_t i = 0; i < 100; ++i) p[1000 + i] = p[i];  // duplicates too
  auto base = min_cycle_cover_sparse(p, 8);
  std::sort(p.begin(), p.end(), [](XY a, XY b) { return a.x < b.x; });
  auto sorted = min_cycle_cover_sparse(p, 8);
  EXPECT_NEAR(sorted.cost, base.cost, 1e-9 * base.cost);
  expect_permutation(sorted.successor);
}

TEST(PoiAssignment, SeparatedPairsBecomeTwoCycles) {
  // Three tight pairs far apart: the optimum swaps within each pair.
  std::vector<XY> p = {{0, 0}, {1000, 0}, {0, 1000}, {1, 0}, {1000, 1}, {1, 1000}};
  for (const auto& cover : {min_cycle_cover_dense(p), min_cycle_cover_sparse(p, 3)}) {
    EXPECT_EQ(cover.successor, (std::vector<std::uint32_t>{3, 4, 5, 0, 1, 2}));
    EXPECT_NEAR(cover.cost, 6.0, 1e-9);
  }
}

TEST(PoiAssignment, DegenerateInputs) {
  EXPECT_TRUE(min_cycle_cover_dense({}).successor.empty());
  EXPECT_TRUE(min_cycle_cover_sparse({}, 8).successor.empty());
  EXPECT_EQ(min_cycle_cover_dense({{5, 5}}).successor, std::vector<std::uint32_t>{0});
  EXPECT_EQ(min_cycle_cover_sparse({{5, 5}}, 8).successor, std::vector<std::uint32_t>{0});
  for (const auto& cover : {min_cycle_cover_dense({{0, 0}, {3, 4}}), min_cycle_cover_sparse({{0, 0}, {3, 4}}, 8)}) {
    EXPECT_EQ(cover.successor, (std::vector<std::uint32_t>{1, 0}));
    EXPECT_DOUBLE_EQ(cover.cost, 10.0);
  }
  std::vector<XY> same(50, XY{7, 7});
  auto dense = min_cycle_cover_dense(same);
  expect_permutation(dense.successor);
  EXPECT_EQ(dense.cost, 0.0);
  for (std::uint32_t i = 0; i < same.size(); ++i) EXPECT_NE(dense.successor[i], i);
  auto sparse = min_cycle_cover_sparse(same, 8);  // all candidates tie: must still terminate
  expect_permutation(sparse.successor);
}

TEST(PoiAssignment, NearestNeighboursExcludeThePointItself) {
  auto p = random_points(200, 3);
  p[5] = p[6] = p[7];  // duplicates
  auto nb = k_nearest(p, 4);
  ASSERT_EQ(nb.k, 4u);
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    double last = 0;
    for (std::size_t a = 0; a < nb.k; ++a) {
      std::uint32_t j = nb.index[i * nb.k + a];
      EXPECT_NE(j, i);
      EXPECT_GE(dist(p[i], p[j]), last - 1e-12);
      last = dist(p[i], p[j]);
    }
    // The k-th neighbour is no farther than the k-th by brute force.
    std::vector<double> d;
    for (std::uint32_t j = 0; j < p.size(); ++j)
      if (j != i) d.push_back(dist(p[i], p[j]));
    std::sort(d.begin(), d.end());
    EXPECT_NEAR(last, d[nb.k - 1], 1e-9);
  }
  EXPECT_EQ(k_nearest({{0, 0}, {1, 1}}, 8).k, 1u);
}

}  // namespace
}  // namespace tourmap::poi
