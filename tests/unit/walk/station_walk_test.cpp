// The walk to the nearest stations over hand-made road networks: the walk found is the
// shortest (against Floyd-Warshall on a random network), k and the distance cap are honoured,
// stations on a disconnected piece or reached only over a motorway are not walked to.

#include "walk/station_walk.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace tourmap::walk {
namespace {

// Points near Vaduz, given in metres east/north of an origin (a local equirectangular
// approximation is enough to place them; all lengths below are measured geodesically).
geo::LonLat at(double east_m, double north_m) {
  constexpr double kLat = 47.14, kLon = 9.52, kMetresPerDegree = 111195.0;
  return {kLon + east_m / (kMetresPerDegree * std::cos(kLat * std::numbers::pi / 180)), kLat + north_m / kMetresPerDegree};
}

struct Net {
  model::RoadNetwork net;
  std::uint32_t node(double east_m, double north_m) {
    net.nodes.push_back({static_cast<std::int64_t>(net.nodes.size() + 1), at(east_m, north_m)});
    return static_cast<std::uint32_t>(net.nodes.size() - 1);
  }
  void way(std::vector<std::uint32_t> nodes, const std::string& highway = "residential") {
    net.ways.push_back({static_cast<std::int64_t>(net.ways.size() + 1), highway, "", std::move(nodes)});
  }
  geo::LonLat pos(std::uint32_t n) const { return net.nodes[n].pos; }
  double length(std::uint32_t a, std::uint32_t b) const { return geo::geodesic_distance_m(pos(a), pos(b)); }
};

WalkGraphParams every_vertex() {
  WalkGraphParams p;
  p.min_snap_component = 1;
  return p;
}

// Sum of the geodesic lengths along a path.
double path_length(const std::vector<geo::LonLat>& path) {
  double m = 0;
  for (std::size_t i = 1; i < path.size(); ++i) m += geo::geodesic_distance_m(path[i - 1], path[i]);
  return m;
}

// A street 0..1000 m east with a node every 100 m; stations (own groups) at 730, 140, 420 m,
// 10 m north of it.
struct Street {
  Net n;
  std::vector<WalkTarget> stations;
  Street() {
    std::vector<std::uint32_t> nodes;
    for (int i = 0; i <= 10; ++i) nodes.push_back(n.node(100.0 * i, 0));
    n.way(nodes);
    std::uint32_t group = 0;
    for (double east : {730.0, 140.0, 420.0}) stations.push_back({at(east, 10), group++});
  }
};

TEST(StationWalk, NearestKStationsInOrderAlongTheStreet) {
  Street s;
  const auto g = build_walk_graph(s.n.net, every_vertex());
  WalkQuery q;
  q.from = at(0, -5);
  q.targets = s.stations;
  q.k = 2;
  const auto r = nearest_walks(*g, q);
  ASSERT_TRUE(r.from_snapped);
  ASSERT_EQ(r.walks.size(), 2u);
  EXPECT_EQ(r.walks[0].target, 1u);  // 140 m
  EXPECT_EQ(r.walks[1].target, 2u);  // 420 m
  // Station at 140 m snaps to the vertex at 100 m: 5 m to the street, 100 m along, the leg.
  EXPECT_NEAR(r.walks[0].distance_m,
              geo::geodesic_distance_m(at(0, -5), at(0, 0)) + geo::geodesic_distance_m(at(0, 0), at(100, 0)) +
                  geo::geodesic_distance_m(at(100, 0), at(140, 10)),
              1e-6);
  EXPECT_EQ(r.walks[0].path.size(), 4u);
  for (const auto& w : r.walks) {
    EXPECT_NEAR(path_length(w.path), w.distance_m, 1e-6);
    EXPECT_GE(w.distance_m, w.straight_m);
    EXPECT_NEAR(w.path.front().lon, q.from.lon, 1e-12);
    EXPECT_NEAR(w.path.back().lon, s.stations[w.target].pos.lon, 1e-12);
  }
  EXPECT_LE(r.walks[0].distance_m, r.walks[1].distance_m);
}

TEST(StationWalk, CapLeavesOutFartherStationsAndStopsTheSearch) {
  Street s;
  const auto g = build_walk_graph(s.n.net, every_vertex());
  WalkQuery q;
  q.from = at(0, 0);
  q.targets = s.stations;
  q.k = 5;
  q.max_m = 550;  // 140 and 420 m are in; 730 m is not
  const auto r = nearest_walks(*g, q);
  ASSERT_EQ(r.walks.size(), 2u);
  for (const auto& w : r.walks) EXPECT_LE(w.distance_m, q.max_m);
  EXPECT_EQ(r.walks[0].target, 1u);
  EXPECT_EQ(r.walks[1].target, 2u);
  EXPECT_EQ(r.settled, 7u);  // vertices at 0..500 m, then the one past the cap stops it
  EXPECT_EQ(r.candidates, 2u);  // the 730 m station is farther than the cap in a straight line

  q.max_m = 100;
  EXPECT_TRUE(nearest_walks(*g, q).walks.empty());
}

TEST(StationWalk, KStopsTheSearchEarly) {
  Street s;
  const auto g = build_walk_graph(s.n.net, every_vertex());
  WalkQuery q;
  q.from = at(0, 0);
  q.targets = s.stations;
  q.k = 1;
  q.max_m = 5000;
  const auto r = nearest_walks(*g, q);
  ASSERT_EQ(r.walks.size(), 1u);
  EXPECT_EQ(r.walks[0].target, 1u);
  EXPECT_EQ(r.settled, 3u);  // 0 and 100 m, then at 200 m the 141 m walk is final
}

TEST(StationWalk, DisconnectedStationIsNotReturned) {
  Street s;
  // An island footway 30 m north of the street's start, not joined to it, with a station on it.
  const auto a = s.n.node(0, 30), b = s.n.node(40, 30);
  s.n.way({a, b}, "footway");
  s.stations.push_back({at(20, 32), 9});
  WalkQuery q;
  q.from = at(0, -2);
  q.targets = s.stations;
  q.k = 5;
  {
    const auto g = build_walk_graph(s.n.net, every_vertex());
    EXPECT_EQ(g->component[0], 0u);  // the street is the largest piece
    const auto r = nearest_walks(*g, q);
    ASSERT_EQ(r.walks.size(), 3u);
    for (const auto& w : r.walks) EXPECT_NE(w.target, 3u);
  }
  {
    // Pieces of 2 vertices are no snap targets: the island's station snaps to the street.
    WalkGraphParams p;
    p.min_snap_component = 3;
    const auto g = build_walk_graph(s.n.net, p);
    const auto r = nearest_walks(*g, q);
    ASSERT_EQ(r.walks.size(), 4u);
    EXPECT_EQ(r.walks[0].target, 3u);
  }
}

TEST(StationWalk, MotorwaysAreNotWalked) {
  Net n;
  // A motorway straight east 0 -> 1000 m, and a road around it through (500, 400).
  const auto w = n.node(0, 0), e = n.node(1000, 0), mid = n.node(500, 400);
  n.way({w, e}, "motorway");
  n.way({w, mid, e}, "tertiary");
  const auto g = build_walk_graph(n.net, every_vertex());
  EXPECT_EQ(g->skipped_ways, 1u);
  WalkQuery q;
  q.from = n.pos(w);
  q.targets = {{n.pos(e), 0}};
  q.max_m = 5000;
  const auto r = nearest_walks(*g, q);
  ASSERT_EQ(r.walks.size(), 1u);
  EXPECT_NEAR(r.walks[0].distance_m, n.length(w, mid) + n.length(mid, e), 1e-6);
  EXPECT_EQ(r.walks[0].path.size(), 3u);

  // Reached only over the motorway: no walk.
  Net m;
  const auto a = m.node(0, 0), b = m.node(1000, 0), c = m.node(1100, 0);
  m.way({a, b}, "motorway");
  m.way({b, c}, "residential");
  m.way({a, m.node(0, 100)}, "residential");
  const auto gm = build_walk_graph(m.net, every_vertex());
  q.from = m.pos(a);
  q.targets = {{m.pos(c), 0}};
  EXPECT_TRUE(nearest_walks(*gm, q).walks.empty());
}

TEST(StationWalk, OneWalkPerGroupToItsNearestMember) {
  Street s;
  const auto g = build_walk_graph(s.n.net, every_vertex());
  WalkQuery q;
  q.from = at(0, 0);
  q.targets = {{at(600, 0), 7}, {at(300, 0), 7}, {at(900, 0), 8}};
  q.k = 2;
  const auto r = nearest_walks(*g, q);
  ASSERT_EQ(r.walks.size(), 2u);
  EXPECT_EQ(r.walks[0].target, 1u);
  EXPECT_NEAR(r.walks[0].distance_m, geo::geodesic_distance_m(at(0, 0), at(300, 0)), 1e-3);
  EXPECT_EQ(r.walks[1].target, 2u);
}

TEST(StationWalk, PointFarFromAnyRoadHasNoWalks) {
  Street s;
  const auto g = build_walk_graph(s.n.net, every_vertex());
  WalkQuery q;
  q.from = at(500, 400);  // 400 m from the street, more than max_snap_m
  q.targets = s.stations;
  const auto r = nearest_walks(*g, q);
  EXPECT_FALSE(r.from_snapped);
  EXPECT_TRUE(r.walks.empty());
  q.max_snap_m = 450;
  EXPECT_EQ(nearest_walks(*g, q).walks.size(), 3u);
}

// Random street networks with points off the roads: every walk is as long as the legs to the
// road and the shortest path Floyd-Warshall finds between, and as long as its path.
TEST(StationWalk, ShortestAgainstFloydWarshall) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> coord(0, 1500);
  for (int round = 0; round < 5; ++round) {
    Net n;
    const std::size_t count = 40;
    for (std::size_t i = 0; i < count; ++i) n.node(coord(rng), coord(rng));
    // Each node joined to its 2 nearest (a sparse, partly disconnected network).
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<std::vector<double>> d(count, std::vector<double>(count, inf));
    for (std::uint32_t i = 0; i < count; ++i) {
      d[i][i] = 0;
      std::vector<std::pair<double, std::uint32_t>> near;
      for (std::uint32_t j = 0; j < count; ++j)
        if (j != i) near.push_back({n.length(i, j), j});
      std::sort(near.begin(), near.end());
      for (std::size_t r = 0; r < 2; ++r) {
        const auto j = near[r].second;
        n.way({i, j});
        d[i][j] = d[j][i] = std::min(d[i][j], near[r].first);
      }
    }
    for (std::size_t m = 0; m < count; ++m)
      for (std::size_t i = 0; i < count; ++i)
        for (std::size_t j = 0; j < count; ++j) d[i][j] = std::min(d[i][j], d[i][m] + d[m][j]);
    const auto g = build_walk_graph(n.net, every_vertex());
    // Points up to 200 m off the nodes (the legs to the road count, and a long leg found early
    // must not be taken for a near station), with their nearest node
    // found by brute force.
    std::uniform_real_distribution<double> off(-150, 150);
    const auto off_node = [&](std::uint32_t i) {
      const auto p = n.net.nodes[i].pos;
      return geo::LonLat{p.lon + off(rng) * 1.3e-5, p.lat + off(rng) * 0.9e-5};
    };
    const auto nearest_node = [&](geo::LonLat p) {
      std::uint32_t best = 0;
      for (std::uint32_t j = 1; j < count; ++j)
        if (geo::geodesic_distance_m(p, n.pos(j)) < geo::geodesic_distance_m(p, n.pos(best))) best = j;
      return best;
    };
    std::vector<WalkTarget> targets;
    std::vector<std::uint32_t> target_node;
    for (std::uint32_t t = 0; t < count; t += 3) {
      targets.push_back({off_node(t), static_cast<std::uint32_t>(targets.size())});
      target_node.push_back(nearest_node(targets.back().pos));
    }
    for (std::uint32_t start = 0; start < count; start += 2) {
      WalkQuery q;
      q.from = off_node(start);
      const auto from = nearest_node(q.from);
      const double from_leg = geo::geodesic_distance_m(q.from, n.pos(from));
      q.targets = targets;
      q.k = 2;
      q.max_m = 1200;
      const auto r = nearest_walks(*g, q);
      // Expected: the 2 nearest targets within the cap by Floyd-Warshall distance and the legs.
      std::vector<double> total(targets.size());
      std::vector<double> expected;
      for (std::size_t t = 0; t < targets.size(); ++t) {
        total[t] = from_leg + d[from][target_node[t]] + geo::geodesic_distance_m(targets[t].pos, n.pos(target_node[t]));
        if (total[t] <= q.max_m) expected.push_back(total[t]);
      }
      std::sort(expected.begin(), expected.end());
      if (expected.size() > 2) expected.resize(2);
      ASSERT_EQ(r.walks.size(), expected.size()) << "round " << round << " from " << start;
      for (std::size_t i = 0; i < expected.size(); ++i) {
        const auto& w = r.walks[i];
        EXPECT_NEAR(w.distance_m, expected[i], 1e-6);
        EXPECT_NEAR(w.distance_m, total[w.target], 1e-6);
        EXPECT_NEAR(path_length(w.path), w.distance_m, 1e-6);
      }
    }
  }
}

TEST(WalkGraph, WalkableClassesAndPieces) {
  EXPECT_TRUE(is_walkable("footway"));
  EXPECT_TRUE(is_walkable("residential"));
  EXPECT_TRUE(is_walkable("trunk"));
  EXPECT_FALSE(is_walkable("motorway"));
  EXPECT_FALSE(is_walkable("motorway_link"));
  Street s;
  const auto a = s.n.node(0, 300), b = s.n.node(40, 300);
  s.n.way({a, b}, "footway");
  const auto g = build_walk_graph(s.n.net);  // default: pieces under 20 vertices are not snapped to
  EXPECT_EQ(g->vertex_count(), 13u);
  EXPECT_EQ(g->edge_count(), 11u);
  EXPECT_EQ(g->snap_vertices, 0u);  // the street has 11 vertices
  EXPECT_FALSE(snap_to_road(*g, at(0, 0)).found);
  const auto all = build_walk_graph(s.n.net, every_vertex());
  EXPECT_EQ(all->snap_vertices, 13u);
  EXPECT_EQ(all->component[11], 1u);  // the footway: the second largest piece
  const auto snap = snap_to_road(*all, at(38, 290));
  ASSERT_TRUE(snap.found);
  EXPECT_EQ(snap.vertex, 12u);
  EXPECT_NEAR(snap.metres, geo::geodesic_distance_m(at(38, 290), at(40, 300)), 1e-9);
}

}  // namespace
}  // namespace tourmap::walk
