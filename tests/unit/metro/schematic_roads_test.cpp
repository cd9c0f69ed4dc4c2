#include "metro/schematic_roads.hpp"

#include "deform/foldover.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace tourmap::metro {
namespace {

const geo::LocalProjection kTown{{9.52, 47.14}};
constexpr int kSide = 21;         // nodes along each side
constexpr double kSpacing = 50;   // metres between them

// A town of kSide x kSide street corners, kSpacing apart: one residential way per row and per
// column, a primary road along the middle row, and a footpath off the grid.
model::RoadNetwork town() {
  model::RoadNetwork net;
  const double half = (kSide - 1) * kSpacing / 2;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i)
      net.nodes.push_back({j * kSide + i + 1, geo::unproject(kTown, {i * kSpacing - half, j * kSpacing - half})});
  auto at = [](int i, int j) { return static_cast<std::uint32_t>(j * kSide + i); };
  for (int j = 0; j < kSide; ++j) {
    model::RoadWay row{1000 + j, j == kSide / 2 ? "primary" : "residential", "", {}};
    for (int i = 0; i < kSide; ++i) row.nodes.push_back(at(i, j));
    net.ways.push_back(row);
  }
  for (int i = 0; i < kSide; ++i) {
    model::RoadWay column{2000 + i, "residential", "", {}};
    for (int j = 0; j < kSide; ++j) column.nodes.push_back(at(i, j));
    net.ways.push_back(column);
  }
  net.nodes.push_back({9001, geo::unproject(kTown, {half + 20, half + 20})});
  net.nodes.push_back({9002, geo::unproject(kTown, {half + 80, half + 80})});
  const auto path0 = static_cast<std::uint32_t>(kSide * kSide);  // the two nodes just added
  net.ways.push_back({3000, "footway", "", {at(kSide - 1, kSide - 1), path0, path0 + 1}});
  net.edges = model::edges_of(net.ways);
  return net;
}

// The schematic's frame: half the metres, turned by 10 degrees and moved (what the Helmert fit
// has to find), plus each station's own displacement.
geo::XY to_layout(geo::XY metres) {
  const double c = std::cos(10 * M_PI / 180), s = std::sin(10 * M_PI / 180);
  return {0.5 * (c * metres.x - s * metres.y) + 3000, 0.5 * (s * metres.x + c * metres.y) - 700};
}

SchematicStation station(int i, int j, geo::XY moved) {
  const double half = (kSide - 1) * kSpacing / 2;
  const geo::XY m{i * kSpacing - half, j * kSpacing - half};
  const auto l = to_layout(m);
  return {geo::unproject(kTown, m), {l.x + moved.x, l.y + moved.y}};
}

// Four stations, three of them moved by 25-35 layout units (50-70 m, a block or more).
std::vector<SchematicStation> four_stations() {
  return {station(5, 5, {30, 0}), station(15, 5, {0, 0}), station(15, 15, {-25, 20}), station(5, 15, {0, -35})};
}

double nearest_point_distance(const std::vector<SchematicRoad>& roads, geo::XY p) {
  double best = 1e300;
  for (const auto& r : roads)
    for (const auto& q : r.points) best = std::min(best, std::hypot(q.x - p.x, q.y - p.y));
  return best;
}

TEST(SchematicRoads, GuidedNodesReachTheirStationsWithoutFolds) {
  const auto stations = four_stations();
  const auto result = schematic_roads(town(), stations);
  const auto& s = result.stats;
  EXPECT_EQ(s.stations, 4u);
  EXPECT_EQ(s.guides, 4u);
  EXPECT_EQ(s.far_stations, 0u);
  EXPECT_NEAR(s.helmert_scale, 2.0, 0.2);  // metres per layout unit
  EXPECT_NEAR(s.helmert_rotation_deg, -10.0, 10.0);  // the moves pull it a little
  EXPECT_GT(s.helmert_max, 10.0);  // the moves are left to the deformation
  // The guided corners land within a layout unit (2 m) of their stations' layout positions.
  EXPECT_LT(s.max_guide_error, 1.0);
  for (const auto& st : stations) EXPECT_LT(nearest_point_distance(result.roads, st.layout), 1.0);
  EXPECT_LT(s.max_station_error, 1.0);
  EXPECT_EQ(s.foldovers, 0u);
  // The footway is left out; every street is there, whole.
  EXPECT_EQ(result.roads.size(), 2u * kSide);
  EXPECT_EQ(s.road_edges, 2u * kSide * (kSide - 1));
  EXPECT_EQ(result.roads[kSide / 2].rank, RoadRank::major);
  EXPECT_EQ(result.roads[0].rank, RoadRank::minor);

  // No two streets cross that did not meet before: the corners shared by a row and a column
  // come out at one point, so rebuild the network from the polylines and count crossings.
  std::map<std::pair<double, double>, std::uint32_t> node_at;
  std::vector<geo::XY> nodes;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& r : result.roads) {
    std::uint32_t previous = 0;
    for (std::size_t k = 0; k < r.points.size(); ++k) {
      auto [it, added] = node_at.emplace(std::make_pair(r.points[k].x, r.points[k].y), nodes.size());
      if (added) nodes.push_back(r.points[k]);
      if (k > 0) edges.emplace_back(previous, it->second);
      previous = it->second;
    }
  }
  EXPECT_GT(s.edge_points, 0u);  // 50 m edges, drawn through a point every 25 m
  EXPECT_EQ(nodes.size(), static_cast<std::size_t>(kSide * kSide) + s.edge_points);
  EXPECT_EQ(deform::count_crossings(nodes, edges), 0u);
  EXPECT_EQ(s.crossings_added, 0u);
}

TEST(SchematicRoads, AHelmertLayoutNeedsNoDeformation) {
  // The layout is the geography turned, scaled and moved: the fit does it all.
  const std::vector<SchematicStation> stations = {station(5, 5, {0, 0}), station(15, 5, {0, 0}), station(15, 15, {0, 0})};
  const auto s = schematic_roads(town(), stations).stats;
  EXPECT_NEAR(s.helmert_rotation_deg, -10.0, 0.05);
  EXPECT_NEAR(s.helmert_scale, 2.0, 0.01);
  EXPECT_LT(s.helmert_max, 0.05);
  EXPECT_LT(s.max_guide_error, 0.05);
  EXPECT_LT(s.max_station_error, 0.05);
}

TEST(SchematicRoads, FarStationsGetNoGuideAndOneNodeOneGuide) {
  auto stations = four_stations();
  // 2 km off the town: no guide. 10 m from a guided corner: shares its node, the nearer wins.
  const double half = (kSide - 1) * kSpacing / 2;
  stations.push_back({geo::unproject(kTown, {half + 2000, 0}), to_layout({half + 2000, 0})});
  stations.push_back({geo::unproject(kTown, {5 * kSpacing - half + 10, 5 * kSpacing - half}),
                      to_layout({5 * kSpacing - half + 10, 5 * kSpacing - half})});
  const auto result = schematic_roads(town(), stations);
  EXPECT_EQ(result.stats.far_stations, 1u);
  EXPECT_EQ(result.stats.shared_nodes, 1u);
  EXPECT_EQ(result.stats.guides, 4u);
}

TEST(SchematicRoads, TheEdgeBoundDropsTheMinorRoadsFirst) {
  SchematicRoadsParams params;
  params.max_edges = 100;  // the primary road's 20 edges fit, the residential streets do not
  const auto result = schematic_roads(town(), four_stations(), params);
  EXPECT_EQ(result.stats.ranks_kept, 2);  // major and medium (none here); not minor
  EXPECT_EQ(result.stats.road_edges, static_cast<std::size_t>(kSide - 1));
  EXPECT_EQ(result.stats.dropped_edges, 2u * kSide * (kSide - 1) - (kSide - 1));
  ASSERT_EQ(result.roads.size(), 1u);
  EXPECT_EQ(result.roads[0].rank, RoadRank::major);
}

TEST(SchematicRoads, CropsToTheStationsAndRefusesOneStation) {
  SchematicRoadsParams params;
  params.margin_min_m = 1;  // a metre: the box is cut in another projection than the town's
  params.margin_share = 0;
  // Stations on the corners (5, 5) and (15, 15): only the streets inside that box stay.
  const std::vector<SchematicStation> two = {station(5, 5, {0, 0}), station(15, 15, {0, 0})};
  const auto result = schematic_roads(town(), two, params);
  EXPECT_EQ(result.stats.road_edges, 2u * 11 * 10);
  EXPECT_GT(result.stats.cropped_out_edges, 0u);
  EXPECT_THROW(schematic_roads(town(), {station(5, 5, {0, 0})}), std::invalid_argument);
  EXPECT_EQ(road_rank("secondary"), RoadRank::medium);
  EXPECT_EQ(road_rank("service"), std::nullopt);
}

}  // namespace
}  // namespace tourmap::metro

