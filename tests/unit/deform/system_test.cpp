// Each objective on tiny systems with known solutions, and the two solvers agreeing.

#include "deform/applications.hpp"
#include "deform/deformer.hpp"
#include "load/osm_roads.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

namespace tourmap::deform {
namespace {

PlanarNetwork path_network(std::vector<XY> nodes) {
  PlanarNetwork net;
  net.nodes = std::move(nodes);
  for (std::uint32_t i = 1; i < net.nodes.size(); ++i) net.edges.emplace_back(i - 1, i);
  return net;
}

RunResult run_with(Prepared& p, const PlanarNetwork& net, const Targets& t, SolverKind kind) {
  RunOptions o;
  o.solve.kind = kind;
  o.solve.tolerance = 1e-13;
  return run(p, net, t, o);
}

TEST(Residue, HandComputed) {
  auto net = path_network({{0, 0}, {1, 0}});
  Targets t{{2.0}, {{1, {3, 4}}}};
  // edge: (1,0) - 2*(1,0) = (-1, 0) -> 1; guide: (1,0) vs (3,4) -> 4 + 16 = 20
  EXPECT_DOUBLE_EQ(residue(net, t, net.nodes), 21.0);
}

TEST(EdgeLevel, ScaledPathBetweenFixedEndsSplitsTheDifference) {
  // A - B - C on a line; the hull (A, C) is fixed; both edges want twice their length.
  auto net = path_network({{0, 0}, {1, 0}, {2, 0}});
  auto p = prepare_edges(net, {}, Weights{});
  EXPECT_EQ(p.rest_unknowns.size(), 2);  // only B moves
  Targets t{{2.0, 2.0}, {}};
  for (auto kind : {SolverKind::cholesky, SolverKind::cg}) {
    auto r = run_with(p, net, t, kind);
    EXPECT_NEAR(r.nodes[1].x, 1.0, 1e-6);  // symmetric: B stays in the middle
    EXPECT_NEAR(r.residue, 2.0, 1e-6);     // each edge is 1 short of its target
  }
}

TEST(EdgeLevel, GuidePullsAgainstTheEdges) {
  // minimise |B - A - d1|^2 + |C - B - d2|^2 + w |B - T|^2  =>  B = (A + d1 + C - d2 + w T) / (2 + w)
  auto net = path_network({{0, 0}, {1, 0}, {2, 0}});
  Weights w;
  w.guide = 4.0;
  auto p = prepare_edges(net, {1}, w);
  XY target{1.0, 3.0};
  Targets t{{}, {{1, target}}};
  auto r = run_with(p, net, t, SolverKind::cholesky);
  // d1 = d2 = (1, 0): numerator x = 0 + 1 + 2 - 1 + 4*1 = 6, y = 4*3 = 12
  EXPECT_NEAR(r.nodes[1].x, 6.0 / 6.0, 1e-5);
  EXPECT_NEAR(r.nodes[1].y, 12.0 / 6.0, 1e-5);
}

TEST(GridSystem, RestStateSatisfiesEveryObjective) {
  // With no request (scale 1, guides at their rest positions) every row is satisfied at rest,
  // including quad shape, support edges and smoothing on an adaptive grid with T-junctions.
  std::vector<XY> nodes;
  for (int i = 0; i < 60; ++i) nodes.push_back({0.5 + 0.05 * i, 0.4 + 0.03 * i});
  auto net = path_network(nodes);
  auto g = grid::build_adaptive(grid::frame_around(net.nodes, 4), net.nodes, {}, {4, 3, 2});
  ASSERT_FALSE(g.tjunctions.empty());
  for (auto boundary : {Boundary::fixed, Boundary::sliding}) {
    auto p = prepare_grid(net, g, {10, 30}, Weights{}, boundary);
    Targets t{{}, {{10, nodes[10]}, {30, nodes[30]}}};
    Eigen::VectorXd b = p.system.base_target;
    b[static_cast<Eigen::Index>(p.system.guide_row_begin)] = p.system.guide_scale * nodes[10].x;
    b[static_cast<Eigen::Index>(p.system.guide_row_begin + 1)] = p.system.guide_scale * nodes[10].y;
    b[static_cast<Eigen::Index>(p.system.guide_row_begin + 2)] = p.system.guide_scale * nodes[30].x;
    b[static_cast<Eigen::Index>(p.system.guide_row_begin + 3)] = p.system.guide_scale * nodes[30].y;
    Eigen::VectorXd residual = p.system.A * p.rest_unknowns - (b - p.system.fixed_part);
    EXPECT_LT(residual.norm(), 1e-9);
    auto r = run_with(p, net, t, SolverKind::cholesky);
    EXPECT_LT(r.residue, 1e-12);
    for (std::size_t i = 0; i < nodes.size(); ++i) EXPECT_NEAR(r.nodes[i].x, nodes[i].x, 1e-9);
  }
}

TEST(GridSystem, StrongGuideReachesItsTarget) {
  // A uniform 2x2 grid: only the centre vertex is free. A node at the centre with a dominant
  // guide must end on the target.
  auto net = path_network({{1, 1}, {1.5, 1.5}});
  auto g = grid::build_uniform({{0, 0}, 1.0, 2, 2});
  Weights w;
  w.guide = 1e8;
  auto p = prepare_grid(net, g, {0}, w, Boundary::fixed);
  EXPECT_EQ(p.rest_unknowns.size(), 2);
  Targets t{{}, {{0, {1.2, 0.9}}}};
  auto r = run_with(p, net, t, SolverKind::cholesky);
  EXPECT_NEAR(r.nodes[0].x, 1.2, 1e-5);
  EXPECT_NEAR(r.nodes[0].y, 0.9, 1e-5);
}

TEST(GridSystem, QuadShapeAloneKeepsAFreeQuadSimilar) {
  // One quad, sliding outline: corners fixed, so the shape term keeps it exactly at rest even
  // when a (weak) guide pulls; the guide is the only thing that could move it.
  auto net = path_network({{0.3, 0.3}, {0.6, 0.6}});
  auto g = grid::build_uniform({{0, 0}, 1.0, 1, 1});
  auto p = prepare_grid(net, g, {}, Weights{}, Boundary::sliding);
  EXPECT_EQ(p.rest_unknowns.size(), 0);  // a single quad's vertices are all frame corners
}

TEST(Solvers, CholeskyAndCgAgreeOnARealNetwork) {
  auto roads = load::load_osm_roads(test::data_file("roads/West-Oakland.osm.bz2"));
  auto net = make_planar(roads);
  Targets t;
  t.edge_scale = focus_edge_scales(net, {{{}, {0, 0}, 200.0, 3.0}});
  auto g = grid::build_adaptive(grid::frame_around(net.nodes, 10), net.nodes, {}, {10, 3, 4});
  auto p = prepare_grid(net, g, {}, Weights{}, Boundary::fixed);
  auto direct = run_with(p, net, t, SolverKind::cholesky);
  auto iterative = run_with(p, net, t, SolverKind::cg);
  EXPECT_TRUE(iterative.solve.converged);
  EXPECT_GT(iterative.solve.iterations, 0);
  EXPECT_NEAR(direct.residue, iterative.residue, 1e-6 * direct.residue);
  double worst = 0;
  for (std::size_t i = 0; i < direct.nodes.size(); ++i)
    worst = std::max({worst, std::abs(direct.nodes[i].x - iterative.nodes[i].x),
                      std::abs(direct.nodes[i].y - iterative.nodes[i].y)});
  EXPECT_LT(worst, 1e-5);
  EXPECT_LT(direct.residue, residue(net, t, net.nodes));  // the deformation helped
  // The factorization is re-used on the next request.
  auto again = run_with(p, net, t, SolverKind::cholesky);
  EXPECT_TRUE(again.solve.factor_cached);
}

TEST(Solvers, CgStopsAtTheIterationCapAndSaysSo) {
  auto roads = load::load_osm_roads(test::data_file("roads/West-Oakland.osm.bz2"));
  auto net = make_planar(roads);
  Targets t;
  t.edge_scale = focus_edge_scales(net, {{{}, {0, 0}, 200.0, 3.0}});
  auto p = prepare_edges(net, {}, Weights{});
  RunOptions o;
  o.solve.kind = SolverKind::cg;
  o.solve.max_iterations = 3;
  auto r = run(p, net, t, o);
  EXPECT_EQ(r.solve.iterations, 3);
  EXPECT_FALSE(r.solve.converged);
  EXPECT_GT(r.solve.relative_residual, 1e-8);
}

}  // namespace
}  // namespace tourmap::deform
