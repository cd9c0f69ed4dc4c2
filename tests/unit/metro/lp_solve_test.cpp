#include "metro/lp_solve.hpp"

#include <gtest/gtest.h>

namespace tourmap::metro {
namespace {

// min x + y  s.t.  x + 2y >= 4,  3x + y >= 6,  x, y >= 0: the corner (1.6, 1.2), value 2.8.
TEST(LpSolve, FindsTheOptimalCorner) {
  MipModel m;
  const int x = m.add_column(0, 1e30, 1, false, 0), y = m.add_column(0, 1e30, 1, false, 0);
  m.add_row({{x, 1}, {y, 2}}, 4, 1e30);
  m.add_row({{x, 3}, {y, 1}}, 6, 1e30);
  auto r = solve_lp_with_clp(m, 5);
  EXPECT_EQ(r.status, "optimal");
  ASSERT_EQ(r.x.size(), 2u);
  EXPECT_NEAR(r.x[0], 1.6, 1e-7);
  EXPECT_NEAR(r.x[1], 1.2, 1e-7);
  EXPECT_NEAR(r.objective, 2.8, 1e-7);
  EXPECT_LE(max_violation(m, r.x), 1e-7);
}

// Free columns (CBC's +-1e30 bounds are CLP's infinity) and an equality row.
TEST(LpSolve, FreeColumnsAndEqualities) {
  MipModel m;
  const int x = m.add_column(-1e30, 1e30, 0, false, 0), t = m.add_column(0, 1e30, 1, false, 0);
  m.add_row({{x, 1}}, -7, -7);                 // x = -7
  m.add_row({{t, 1}, {x, 1}}, 0, 1e30);        // t >= -x
  auto r = solve_lp_with_clp(m, 5);
  EXPECT_EQ(r.status, "optimal");
  ASSERT_EQ(r.x.size(), 2u);
  EXPECT_NEAR(r.x[0], -7, 1e-7);
  EXPECT_NEAR(r.x[1], 7, 1e-7);
}

TEST(LpSolve, InfeasibleHasNoSolution) {
  MipModel m;
  const int x = m.add_column(0, 1, 1, false, 0);
  m.add_row({{x, 1}}, 2, 1e30);
  auto r = solve_lp_with_clp(m, 5);
  EXPECT_EQ(r.status, "infeasible");
  EXPECT_TRUE(r.x.empty());
}

// A session solved, then cut (a row the solution violates, with a new column in it) and
// solved again from its basis: the same optimum as the whole program solved at once.
TEST(LpSolve, SessionResolvesWithCuts) {
  MipModel m;
  const int x = m.add_column(0, 1e30, 1, false, 0), y = m.add_column(0, 1e30, 1, false, 0);
  m.add_row({{x, 1}, {y, 2}}, 4, 1e30);
  LpSession lp(m);
  auto first = lp.solve(5);
  ASSERT_EQ(first.status, "optimal");
  EXPECT_NEAR(first.objective, 2.0, 1e-7);  // (0, 2)
  // Cut: 3x + y + z >= 6 with z >= 0 at cost 10 (a priced slack).
  const int z = lp.add_column(0, 1e30, 10);
  EXPECT_EQ(z, 2);
  lp.add_row({{x, 3}, {y, 1}, {z, 1}}, 6, 1e30);
  EXPECT_EQ(lp.columns(), 3u);
  EXPECT_EQ(lp.rows(), 2u);
  auto second = lp.resolve(5);
  ASSERT_EQ(second.status, "optimal");
  ASSERT_EQ(second.x.size(), 3u);
  EXPECT_NEAR(second.x[0], 1.6, 1e-7);
  EXPECT_NEAR(second.x[1], 1.2, 1e-7);
  EXPECT_NEAR(second.x[2], 0.0, 1e-7);
  EXPECT_NEAR(second.objective, 2.8, 1e-7);
  // Terms on one column are summed: x + x >= 5 is 2x >= 5.
  lp.add_row({{x, 1}, {x, 1}}, 5, 1e30);
  auto third = lp.resolve(5);
  ASSERT_EQ(third.status, "optimal");
  EXPECT_NEAR(third.x[0], 2.5, 1e-7);
}

}  // namespace
}  // namespace tourmap::metro
