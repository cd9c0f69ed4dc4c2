#include "metro/station_spacing.hpp"

#include "metro/layout_quality.hpp"
#include "metro/station_gap.hpp"
#include "util/stop.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace tourmap::metro {
namespace {

// Two parallel lines of three stations, 10 apart along the line but only 2 apart across: every
// station is a fifth of the mean edge from the other line. The first line also has a bend.
struct Parallel {
  LayoutGraph g;
  Layout layout;
};

Parallel parallel_lines() {
  Parallel n;
  n.g.pos = {{0, 0}, {1000, 0}, {2000, 0}, {0, 200}, {1000, 200}, {2000, 200}};
  n.g.edges = {{0, 1}, {1, 2}, {3, 4}, {4, 5}};
  n.g.edge_lines = {{0}, {0}, {1}, {1}};
  n.g.min_length.assign(4, 10.0);
  n.layout.pos = {{0, 0}, {10, 0}, {20, 0}, {0, 2}, {10, 2}, {20, 2}};
  n.layout.paths = {{{0, 0}, {10, 0}}, {{10, 0}, {15, 0}, {20, 0}}, {{0, 2}, {10, 2}}, {{10, 2}, {20, 2}}};
  // A bend on the second edge of the first line: down and back up at 45 degrees.
  n.layout.pos[2] = {20, -4};
  n.layout.paths[1] = {{10, 0}, {16, 0}, {20, -4}};
  return n;
}

double ratio(const LayoutGraph& g, const Layout& L) {
  auto q = measure_layout(g, L);
  return q.min_station_gap / q.mean_edge;
}

std::vector<double> directions(const Layout& L) {
  std::vector<double> out;
  for (const auto& path : L.paths)
    for (std::size_t i = 1; i < path.size(); ++i)
      out.push_back(std::atan2(path[i].y - path[i - 1].y, path[i].x - path[i - 1].x));
  return out;
}

TEST(StationSpacing, MovesCrowdedLinesApartKeepingEveryDirection) {
  auto n = parallel_lines();
  const auto before = measure_layout(n.g, n.layout);
  ASSERT_LT(ratio(n.g, n.layout), 0.3);
  const auto dirs = directions(n.layout);
  auto report = space_stations(n.g, n.layout);
  EXPECT_EQ(report.status, "met");
  EXPECT_GE(report.accepted, 1);
  EXPECT_LT(report.gap_before, 0.3);
  EXPECT_GE(report.gap_after, 0.5);
  EXPECT_NEAR(report.gap_after, ratio(n.g, n.layout), 1e-9);
  const auto after = measure_layout(n.g, n.layout);
  EXPECT_EQ(after.octilinear_share, 1.0);
  EXPECT_EQ(after.bends, before.bends);
  EXPECT_EQ(after.crossings, 0u);
  EXPECT_EQ(after.order_violations, 0u);
  // Same segments, same directions: only lengths and offsets changed.
  ASSERT_EQ(directions(n.layout).size(), dirs.size());
  for (std::size_t i = 0; i < dirs.size(); ++i) EXPECT_NEAR(directions(n.layout)[i], dirs[i], 1e-6) << i;
  // Every edge still runs between its stations.
  for (std::size_t e = 0; e < n.g.edges.size(); ++e) {
    EXPECT_NEAR(n.layout.paths[e].front().x, n.layout.pos[n.g.edges[e].first].x, 1e-9);
    EXPECT_NEAR(n.layout.paths[e].back().y, n.layout.pos[n.g.edges[e].second].y, 1e-9);
  }
}

TEST(StationSpacing, LeavesARoomyLayoutAlone) {
  auto n = parallel_lines();
  for (auto& p : n.layout.pos) p.y *= 5;  // lines 10 apart
  for (auto& path : n.layout.paths)
    for (auto& p : path) p.y *= 5;
  // The bend is now no longer at 45 degrees: redraw the second edge straight.
  n.layout.pos[2] = {20, 0};
  n.layout.paths[1] = {{10, 0}, {20, 0}};
  const auto copy = n.layout;
  auto report = space_stations(n.g, n.layout);
  EXPECT_EQ(report.status, "met");
  EXPECT_EQ(report.rounds, 0);
  for (std::size_t v = 0; v < copy.pos.size(); ++v) {
    EXPECT_EQ(n.layout.pos[v].x, copy.pos[v].x);
    EXPECT_EQ(n.layout.pos[v].y, copy.pos[v].y);
  }
}

TEST(StationSpacing, SkipsALayoutThatIsNotOctilinear) {
  auto n = parallel_lines();
  n.layout.pos[5] = {20, 5};
  n.layout.paths[3] = {{10, 2}, {20, 5}};  // 17 degrees
  const auto copy = n.layout;
  auto report = space_stations(n.g, n.layout);
  EXPECT_EQ(report.status, "skipped");
  EXPECT_EQ(report.accepted, 0);
  EXPECT_EQ(n.layout.pos[4].y, copy.pos[4].y);
}

// Three parallel lines of three stations at heights ys (edges 10 long, the geography 100 times
// larger).
struct Lines {
  LayoutGraph g;
  Layout L;
};

Lines three_lines(std::array<double, 3> ys) {
  Lines n;
  for (std::uint32_t line = 0; line < 3; ++line) {
    for (int k = 0; k < 3; ++k) {
      n.g.pos.push_back({1000.0 * k, 100 * ys[line]});
      n.L.pos.push_back({10.0 * k, ys[line]});
    }
    for (std::uint32_t k = 0; k < 2; ++k) {
      const std::uint32_t a = 3 * line + k;
      n.g.edges.push_back({a, a + 1});
      n.g.edge_lines.push_back({line});
      n.L.paths.push_back({n.L.pos[a], n.L.pos[a + 1]});
    }
  }
  n.g.min_length.assign(n.g.edges.size(), 10.0);
  return n;
}

// Three parallel lines 1 and 1.5 apart (edges 10 long): the middle one must move away from
// both without passing either, so the lines keep their order and nothing crosses.
TEST(StationSpacing, ASqueezedLineStaysBetweenItsNeighbours) {
  auto [g, L] = three_lines({0, 1, 2.5});
  auto report = space_stations(g, L);
  EXPECT_EQ(report.status, "met");
  EXPECT_GE(ratio(g, L), 0.5);
  EXPECT_EQ(count_path_crossings(L.paths, g.edges), 0u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(L.pos[k].y, L.pos[3 + k].y) << k;
    EXPECT_LT(L.pos[3 + k].y, L.pos[6 + k].y) << k;
  }
}

// Three parallel lines at y = 0, 1 and 8 (edges 10 long). With the program holding only the
// pairs within the rule at the start, the far line is not in it; moving the middle line away
// from the first brings it too close to the far one, and that pair comes in as a cut.
TEST(StationSpacing, PairsBroughtTooCloseAreCutIn) {
  auto [g, L] = three_lines({0, 1, 8});
  SpacingParams p;
  p.pair_radius = 1.0;
  p.cut_radius = 0;
  auto report = space_stations(g, L, p);
  EXPECT_EQ(report.status, "met");
  EXPECT_GT(report.cuts, 0u);
  EXPECT_GE(ratio(g, L), 0.5);
  EXPECT_EQ(count_path_crossings(L.paths, g.edges), 0u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(L.pos[k].y, L.pos[3 + k].y) << k;
    EXPECT_LT(L.pos[3 + k].y, L.pos[6 + k].y) << k;
  }
}

// A request's deadline (or a client that left) stops the pass between its steps, whatever its
// own budget: the layout is left as it was.
TEST(StationSpacing, StopsAtTheRequestsDeadline) {
  auto n = parallel_lines();
  const auto copy = n.layout;
  util::StopToken past;
  past.deadline = util::StopToken::Clock::now() - std::chrono::seconds(1);
  util::StopScope scope(past);
  EXPECT_THROW(space_stations(n.g, n.layout), util::Stopped);
  for (std::size_t v = 0; v < copy.pos.size(); ++v) EXPECT_EQ(n.layout.pos[v].y, copy.pos[v].y);
}

TEST(LabelRoom, MovesALineOutOfANamesBox) {
  // Two parallel lines 2 units apart, mean edge 10: at 75 px a name wanted above the middle
  // station of the lower line (5 to 20 px above it) has the upper line (15 px above) across it.
  // One round of the program moves the upper line clear of the box, every direction kept.
  LayoutGraph g;
  g.pos = {{0, 0}, {1000, 0}, {2000, 0}, {0, 200}, {1000, 200}, {2000, 200}};
  g.edges = {{0, 1}, {1, 2}, {3, 4}, {4, 5}};
  g.edge_lines = {{0}, {0}, {1}, {1}};
  g.min_length.assign(4, 10.0);
  Layout layout;
  layout.pos = {{0, 0}, {10, 0}, {20, 0}, {0, 2}, {10, 2}, {20, 2}};
  layout.paths = {{{0, 0}, {10, 0}}, {{10, 0}, {20, 0}}, {{0, 2}, {10, 2}}, {{10, 2}, {20, 2}}};
  const std::vector<LabelRoom> rooms = {{1, -20, -20, 20, -5}};  // px from the station, y down
  LabelRoomParams params;
  params.scale_px = 75;
  const auto dirs = directions(layout);
  const auto room = make_room_for_labels(g, layout, rooms, {}, params);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(directions(*room), dirs);
  const double mean = measure_layout(g, *room).mean_edge;
  const double px = 75 / mean;  // px per unit at the zoom the box is for
  // The upper line clears the box's top (20 px) by half its width and the clearance (3 px).
  const double above = (room->pos[4].y - room->pos[1].y) * px;
  EXPECT_GE(above, 20 + 3 - 0.1) << above;
  EXPECT_NEAR(room->pos[3].y, room->pos[5].y, 1e-6);  // still a straight line
  // Nothing asked: nothing to do.
  EXPECT_FALSE(make_room_for_labels(g, layout, {}, {}, params).has_value());
}

TEST(LabelRoom, KeepsPlacedNamesClearOfTheLinesItMoves) {
  // The lines of the test above, and a third one 4 units (30 px) below the middle one, whose
  // middle station has its name placed above it (5 to 20 px up): room for the middle station's
  // name can be made by moving the upper line up or the middle one down (into that name); the
  // placed name must stay clear either way. (Here the program moves the upper line even
  // without the placed name's rows; London's rounds are where they count: metro_bench.)
  LayoutGraph g;
  g.pos = {{0, 0}, {1000, 0}, {2000, 0}, {0, 200}, {1000, 200}, {2000, 200}, {0, -400}, {1000, -400}, {2000, -400}};
  g.edges = {{0, 1}, {1, 2}, {3, 4}, {4, 5}, {6, 7}, {7, 8}};
  g.edge_lines = {{0}, {0}, {1}, {1}, {2}, {2}};
  g.min_length.assign(6, 10.0);
  Layout layout;
  layout.pos = {{0, 0}, {10, 0}, {20, 0}, {0, 2}, {10, 2}, {20, 2}, {0, -4}, {10, -4}, {20, -4}};
  for (auto [a, b] : g.edges) layout.paths.push_back({layout.pos[a], layout.pos[b]});
  const std::vector<LabelRoom> rooms = {{1, -20, -20, 20, -5}};
  const std::vector<LabelRoom> placed = {{7, -20, -20, 20, -5}};
  LabelRoomParams params;
  params.scale_px = 75;
  const auto room = make_room_for_labels(g, layout, rooms, placed, params);
  ASSERT_TRUE(room.has_value());
  const double px = 75 / measure_layout(g, *room).mean_edge;
  // The room is made (the upper line clears its top by 3 px) and the placed name's top (20 px
  // above station 7) stays clear of the middle line by its half width and clearance.
  EXPECT_GE((room->pos[4].y - room->pos[1].y) * px, 20 + 3 - 0.1);
  EXPECT_GE((room->pos[1].y - room->pos[7].y) * px, 20 + 3 - 0.1);
}

}  // namespace
}  // namespace tourmap::metro
