#include "grid/embedding.hpp"
#include "grid/grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tourmap::grid {
namespace {

Frame unit_frame(int cols, int rows, double cell = 1.0) { return {{0, 0}, cell, cols, rows}; }

// Level of the leaf covering finest cell (x, y).
int level_at(const Grid& g, int x, int y) {
  int width = g.cols << g.max_level;
  return g.quads[g.cell_quad[static_cast<std::size_t>(y) * width + x]].level;
}

void expect_balanced(const Grid& g) {
  int width = g.cols << g.max_level, height = g.rows << g.max_level;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (x + 1 < width) {
        ASSERT_LE(std::abs(level_at(g, x, y) - level_at(g, x + 1, y)), 1) << x << "," << y;
      }
      if (y + 1 < height) {
        ASSERT_LE(std::abs(level_at(g, x, y) - level_at(g, x, y + 1)), 1) << x << "," << y;
      }
    }
}

TEST(Grid, UniformGridCounts) {
  auto g = build_uniform(unit_frame(4, 3));
  EXPECT_EQ(g.vertices.size(), 5u * 4u);
  EXPECT_EQ(g.quads.size(), 12u);
  EXPECT_TRUE(g.tjunctions.empty());
  EXPECT_EQ(count_grid_edges(g), 4u * 4u + 5u * 3u);  // horizontal + vertical sides
  std::size_t boundary = 0;
  for (bool b : g.on_boundary) boundary += b;
  EXPECT_EQ(boundary, 14u);
  // Interior vertices have four vertex neighbours, outline vertices three, corners two.
  for (std::size_t v = 0; v < g.vertices.size(); ++v) {
    int n = 0;
    for (const auto& nb : g.neighbors[v]) n += nb.kind == Neighbor::Kind::vertex;
    const auto& p = g.vertices[v];
    bool corner = (p.x == 0 || p.x == 4) && (p.y == 0 || p.y == 3);
    EXPECT_EQ(n, corner ? 2 : g.on_boundary[v] ? 3 : 4) << p.x << "," << p.y;
  }
}

TEST(Grid, FrameIsSquareCelledAndCentred) {
  auto f = frame_around({{0, 0}, {100, 50}}, 10, 0.0);
  EXPECT_DOUBLE_EQ(f.cell, 10.0);
  EXPECT_EQ(f.cols, 10);
  EXPECT_EQ(f.rows, 5);
  EXPECT_DOUBLE_EQ(f.origin.x, 0.0);
  auto padded = frame_around({{0, 0}, {100, 50}}, 10);
  EXPECT_LT(padded.origin.x, 0.0);
  EXPECT_LT(padded.origin.y, 0.0);
  EXPECT_THROW(frame_around({{0, 0}}, 0), std::invalid_argument);
}

TEST(Grid, AdaptiveRefinesWhereThePointsAreAndBalances) {
  // 200 points packed into one corner cell of a 4x4 base grid.
  std::vector<XY> points;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> in_corner(0.01, 0.24);
  for (int i = 0; i < 200; ++i) points.push_back({in_corner(rng), in_corner(rng)});
  auto g = build_adaptive(unit_frame(4, 4, 1.0), points, {}, {4, 4, 3});
  expect_balanced(g);
  EXPECT_EQ(g.max_level, 4);
  EXPECT_EQ(g.quads[g.quad_at({0.1, 0.1})].level, 4);  // refined to the maximum where the points are
  EXPECT_EQ(g.quads[g.quad_at({3.5, 3.5})].level, 0);  // untouched far away
  EXPECT_FALSE(g.tjunctions.empty());
  // Every quad holding more than c points is at the maximum depth.
  for (std::uint32_t q = 0; q < g.quads.size(); ++q) {
    int inside = 0;
    for (const auto& p : points) inside += g.quad_at(p) == q;
    if (inside > 3) {
      EXPECT_EQ(g.quads[q].level, 4);
    }
  }
}

TEST(Grid, TJunctionsSitOnCoarseSidesWithACentroidNeighbour) {
  auto g = build_adaptive(unit_frame(3, 3, 1.0), {}, {{1.5, 1.5}}, {3, 2, 1000});  // a special point
  expect_balanced(g);
  ASSERT_FALSE(g.tjunctions.empty());
  for (const auto& t : g.tjunctions) {
    const auto& q = g.quads[t.coarse_quad];
    const auto& a = g.vertices[q.corners[t.side]];
    const auto& b = g.vertices[q.corners[(t.side + 1) % 4]];
    const auto& v = g.vertices[t.vertex];
    EXPECT_NEAR(v.x, (a.x + b.x) / 2, 1e-12);
    EXPECT_NEAR(v.y, (a.y + b.y) / 2, 1e-12);
    // The direction into the coarse quad has no grid edge: its centroid stands in (4.4.1).
    int centroid_neighbours = 0;
    for (const auto& nb : g.neighbors[t.vertex])
      if (nb.kind == Neighbor::Kind::quad_centroid) {
        EXPECT_EQ(nb.index, t.coarse_quad);
        ++centroid_neighbours;
      }
    EXPECT_EQ(centroid_neighbours, 1);
  }
  // Support edges make the smoothing neighbourhood complete: no interior vertex lacks a side.
  for (std::size_t v = 0; v < g.vertices.size(); ++v) {
    if (g.on_boundary[v]) continue;
    for (const auto& nb : g.neighbors[v]) EXPECT_NE(nb.kind, Neighbor::Kind::none) << v;
  }
}

TEST(Grid, SplitThresholdC) {
  std::vector<XY> points = {{0.2, 0.2}, {0.3, 0.3}, {0.6, 0.6}};
  EXPECT_EQ(build_adaptive(unit_frame(1, 1), points, {}, {1, 3, 3}).quads.size(), 1u);  // 3 points, c = 3
  EXPECT_GT(build_adaptive(unit_frame(1, 1), points, {}, {1, 3, 2}).quads.size(), 1u);
}

TEST(Embedding, RoundTripsOnTheRestGrid) {
  std::vector<XY> points;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(0.0, 4.0);
  for (int i = 0; i < 500; ++i) points.push_back({coord(rng), coord(rng)});
  auto g = build_adaptive(unit_frame(4, 4), points, {}, {4, 3, 5});
  for (const auto& p : points) {
    auto e = embed(g, p);
    double sum = e.weight[0] + e.weight[1] + e.weight[2] + e.weight[3];
    EXPECT_NEAR(sum, 1.0, 1e-12);
    auto back = place(g, g.vertices, e);
    EXPECT_NEAR(back.x, p.x, 1e-9);
    EXPECT_NEAR(back.y, p.y, 1e-9);
  }
}

TEST(Embedding, InverseBilinearOnADistortedQuad) {
  std::array<XY, 4> quad = {XY{0, 0}, XY{2.2, 0.3}, XY{2.6, 1.9}, XY{-0.2, 1.4}};
  for (double u : {0.0, 0.1, 0.5, 0.93, 1.0})
    for (double v : {0.0, 0.2, 0.5, 0.77, 1.0}) {
      auto p = bilinear(quad, u, v);
      auto uv = inverse_bilinear(quad, p);
      ASSERT_TRUE(uv) << u << "," << v;
      EXPECT_NEAR((*uv)[0], u, 1e-9);
      EXPECT_NEAR((*uv)[1], v, 1e-9);
    }
  EXPECT_FALSE(inverse_bilinear(quad, {5, 5}));
}

}  // namespace
}  // namespace tourmap::grid
