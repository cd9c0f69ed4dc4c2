// Transit line graphs from OSM route relations (load/metro_osm.hpp): lines from route masters
// (or mode and ref), stations from stop areas and names, the order of stop positions, modes,
// edge geometry from the routes' ways (out of order, reversed, gaps), the problems reported,
// and the extracts of Liechtenstein (train and buses) and Monaco (buses).

#include "load/metro_osm.hpp"
#include "geo/projection.hpp"
#include "load/load_error.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <set>
#include <sstream>

namespace tourmap::load {
namespace {

std::string osm(const std::string& body) {
  return std::string(R"(<?xml version='1.0' encoding='UTF-8'?><osm version="0.6">)") + body + "</osm>";
}

std::string tag(const std::string& k, const std::string& v) { return "<tag k=\"" + k + "\" v=\"" + v + "\"/>"; }

std::string node(long id, double lon, double lat, const std::string& tags = "") {
  std::ostringstream out;
  out.precision(10);
  out << "<node id=\"" << id << "\" lat=\"" << lat << "\" lon=\"" << lon << "\">" << tags << "</node>";
  return out.str();
}

// A relation; members as "n12:stop", "w7:platform", "r5:".
std::string relation(long id, std::initializer_list<std::string> members, const std::string& tags) {
  std::string out = "<relation id=\"" + std::to_string(id) + "\">";
  for (const auto& m : members) {
    const auto colon = m.find(':');
    const std::string type = m[0] == 'n' ? "node" : m[0] == 'w' ? "way" : "relation";
    out += "<member type=\"" + type + "\" ref=\"" + m.substr(1, colon - 1) + "\" role=\"" + m.substr(colon + 1) + "\"/>";
  }
  return out + tags + "</relation>";
}

// A way through the nodes given.
std::string way(long id, std::initializer_list<long> nodes, const std::string& tags = "") {
  std::string out = "<way id=\"" + std::to_string(id) + "\">";
  for (const auto n : nodes) out += "<nd ref=\"" + std::to_string(n) + "\"/>";
  return out + tags + "</way>";
}

std::set<std::pair<std::string, std::string>> edges_by_name(const model::MetroNetwork& net) {
  std::set<std::pair<std::string, std::string>> out;
  for (const auto& e : net.edges) {
    auto a = net.nodes[e.from].name, b = net.nodes[e.to].name;
    out.insert(a < b ? std::pair{a, b} : std::pair{b, a});
  }
  return out;
}

// Three stations on a tram line mapped both ways under a route master; at the middle one a stop
// position and a platform in one stop area, the platform named by its track; an express of the
// line skipping it; a bus route too.
std::string tram_town() {
  return osm(node(1, 10.000, 50.000, tag("public_transport", "stop_position") + tag("name", "Markt")) +
             node(2, 10.010, 50.000, tag("public_transport", "stop_position") + tag("name", "Rathaus")) +
             node(3, 10.0102, 50.0003, tag("public_transport", "platform") + tag("name", "1")) +
             node(4, 10.020, 50.000, tag("public_transport", "stop_position") + tag("name", "Bahnhof")) +
             node(5, 10.0201, 50.0001, tag("public_transport", "platform") + tag("name", "Bahnhof")) +
             relation(10, {"n1:stop", "n2:stop", "n4:stop", "n3:platform", "n5:platform"},
                      tag("type", "route") + tag("route", "tram") + tag("ref", "T1") + tag("colour", "#E2001A")) +
             relation(11, {"n4:stop_entry_only", "n2:stop", "n1:stop_exit_only", "n99:stop"},
                      tag("type", "route") + tag("route", "tram") + tag("ref", "T1")) +
             // An express of the line: Markt straight to Bahnhof, beside the line through Rathausplatz.
             relation(14, {"n1:stop", "n4:stop"}, tag("type", "route") + tag("route", "tram") + tag("ref", "T1")) +
             relation(12, {"r10:", "r11:", "r14:"}, tag("type", "route_master") + tag("route_master", "tram") + tag("ref", "T1") +
                                                tag("name", "Tram 1")) +
             relation(13, {"n2:stop", "n3:platform"}, tag("type", "public_transport") + tag("public_transport", "stop_area") +
                                                          tag("name", "Rathausplatz")) +
             relation(20, {"n1:platform", "n4:platform"}, tag("type", "route") + tag("route", "bus") + tag("ref", "5")));
}

TEST(MetroOsm, RouteMasterStopAreasAndStopOrder) {
  test::TempDir dir;
  const auto path = dir.write("town.osm", tram_town());
  OsmTransitStats stats;
  const auto net = load_metro_osm(path, {}, {}, &stats);  // the rail modes present: tram
  EXPECT_EQ(stats.modes, std::vector<std::string>{"tram"});
  EXPECT_EQ(stats.routes, 3u);
  EXPECT_EQ(stats.route_masters, 1u);
  EXPECT_EQ(stats.skip_edges, 1u);  // the express's Markt - Bahnhof, beside the line
  EXPECT_EQ(stats.missing_stop_members, 1u);  // n99
  ASSERT_EQ(net.lines.size(), 1u);            // both directions: one line
  EXPECT_EQ(net.lines[0].id, "r12");
  EXPECT_EQ(net.lines[0].label, "T1");
  EXPECT_EQ(net.lines[0].color, "e2001a");
  ASSERT_EQ(net.nodes.size(), 3u);  // the stop area's platform "1" is Rathausplatz, Bahnhof's platform Bahnhof
  std::set<std::string> names;
  for (const auto& n : net.nodes) {
    EXPECT_TRUE(n.is_station());
    names.insert(n.name);
  }
  EXPECT_EQ(names, (std::set<std::string>{"Markt", "Rathausplatz", "Bahnhof"}));
  // Stop positions give the order (the platforms listed after them add no Bahnhof - Markt edge).
  EXPECT_EQ(edges_by_name(net), (std::set<std::pair<std::string, std::string>>{{"Markt", "Rathausplatz"}, {"Bahnhof", "Rathausplatz"}}));
  for (const auto& e : net.edges) EXPECT_EQ(e.lines.size(), 1u);
}

TEST(MetroOsm, ModesAskedForAndRoutesWithoutStops) {
  test::TempDir dir;
  const auto path = dir.write("town.osm", tram_town());
  OsmTransitStats stats;
  const auto net = load_metro_osm(path, {"bus", "tram"}, {}, &stats);
  EXPECT_EQ(stats.routes, 4u);
  ASSERT_EQ(net.lines.size(), 2u);
  // The bus line by platforms (it has no stop positions): Markt - Bahnhof, kept (the tram's
  // path through Rathausplatz does not carry the bus).
  EXPECT_TRUE(edges_by_name(net).count({"Bahnhof", "Markt"}));
  EXPECT_EQ(stats.skip_edges, 0u);
  EXPECT_THROW(load_metro_osm(path, {"ferry"}), LoadError);  // no route of that mode
  EXPECT_THROW(load_metro_osm(path, {"hovercraft"}), LoadError);
  const auto lone = dir.write("lone.osm", osm(node(1, 10, 50, tag("name", "A")) +
                                             relation(10, {"n1:stop", "n2:stop"}, tag("type", "route") + tag("route", "bus"))));
  try {
    load_metro_osm(lone, {"bus"}, {}, &stats);
    FAIL() << "a route with one stop in the extract made a network";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("two stops"), std::string::npos) << e.what();
  }
}

const model::MetroEdge* edge_between(const model::MetroNetwork& net, const std::string& a, const std::string& b) {
  for (const auto& e : net.edges) {
    const auto& from = net.nodes[e.from].name;
    const auto& to = net.nodes[e.to].name;
    if ((from == a && to == b) || (from == b && to == a)) return &e;
  }
  return nullptr;
}

// Metres from p to the polyline `line`.
double metres_to(geo::LonLat p, const std::vector<geo::LonLat>& line) {
  double best = 1e18;
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
    for (int k = 0; k <= 100; ++k) {  // sampled: fine to a few metres on these short segments
      const double t = k / 100.0;
      best = std::min(best, geo::geodesic_distance_m(p, {line[i].lon + t * (line[i + 1].lon - line[i].lon),
                                                         line[i].lat + t * (line[i + 1].lat - line[i].lat)}));
    }
  return best;
}

bool same(geo::LonLat a, geo::LonLat b) { return a.lon == b.lon && a.lat == b.lat; }

bool mentions(const OsmTransitStats& stats, long relation, const std::string& part) {
  return std::any_of(stats.problems.begin(), stats.problems.end(), [&](const OsmRouteProblem& p) {
    return p.relation == relation && p.message.find(part) != std::string::npos;
  });
}

// A zigzag road east through nodes 101-107 (bends at 102, 104, 106) in three ways, bus stops
// 50 m beside it (Ost, Mitte, West from east to west). Route 11 runs west to east listing its
// ways out of order (201, 203, 202) and 202 drawn against it; route 10, listed first, runs
// east to west without ways, so its straight edges run from east to west and get route 11's
// track reversed. Route 12 has a real gap: way 302 does not meet 301.
std::string bus_town() {
  const auto bus_stop = [](const std::string& name) { return tag("highway", "bus_stop") + tag("name", name); };
  const auto bus = [](const std::string& ref) { return tag("type", "route") + tag("route", "bus") + tag("ref", ref); };
  return osm(
      node(101, 10.000, 50.000) + node(102, 10.005, 50.002) + node(103, 10.010, 50.000) + node(104, 10.015, 50.002) +
      node(105, 10.020, 50.000) + node(106, 10.025, 50.002) + node(107, 10.030, 50.000) +
      node(1, 10.000, 49.9995, bus_stop("West")) + node(2, 10.020, 49.9995, bus_stop("Mitte")) +
      node(3, 10.030, 49.9995, bus_stop("Ost")) + way(201, {101, 102, 103}, tag("highway", "primary")) +
      way(202, {105, 104, 103}, tag("highway", "primary")) + way(203, {105, 106, 107}, tag("highway", "primary")) +
      relation(10, {"n3:platform", "n2:platform", "n1:platform"}, bus("1")) +
      relation(11, {"n1:platform", "n2:platform", "n3:platform", "w201:", "w203:", "w202:forward"}, bus("1")) +
      // The gap: Nord 1 - Nord 2 on way 301, Nord 3 on way 302 starting 140 m on.
      node(111, 10.000, 50.010) + node(112, 10.005, 50.012) + node(113, 10.010, 50.010) + node(114, 10.012, 50.010) +
      node(115, 10.016, 50.012) + node(116, 10.020, 50.010) + node(4, 10.000, 50.0095, bus_stop("Nord 1")) +
      node(5, 10.010, 50.0095, bus_stop("Nord 2")) + node(6, 10.020, 50.0095, bus_stop("Nord 3")) +
      way(301, {111, 112, 113}) + way(302, {114, 115, 116}) +
      relation(12, {"n4:platform", "n5:platform", "n6:platform", "w301:", "w302:"}, bus("2")));
}

TEST(MetroOsm, EdgesFollowTheWaysOutOfOrderAndReversed) {
  test::TempDir dir;
  const auto path = dir.write("bus.osm", bus_town());
  OsmTransitStats stats;
  const auto net = load_metro_osm(path, {"bus"}, {}, &stats);
  const std::vector<geo::LonLat> road = {{10.000, 50.000}, {10.005, 50.002}, {10.010, 50.000}, {10.015, 50.002},
                                         {10.020, 50.000}, {10.025, 50.002}, {10.030, 50.000}};
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{{"West", "Mitte"}, {"Mitte", "Ost"}}) {
    const auto* e = edge_between(net, a, b);
    ASSERT_TRUE(e) << a << " - " << b;
    const auto& g = e->geometry;
    ASSERT_GE(g.size(), 4u) << a << " - " << b;  // the stations, and the track's bends between them
    // Oriented from `from` to `to`: route 10 made the edge east to west, route 11's track was reversed.
    EXPECT_EQ(net.nodes[e->from].name, b);
    EXPECT_TRUE(same(g.front(), net.nodes[e->from].pos) && same(g.back(), net.nodes[e->to].pos));
    for (std::size_t i = 1; i < g.size(); ++i) EXPECT_LE(g[i].lon, g[i - 1].lon + 1e-12) << "not running east to west";
    for (std::size_t i = 1; i + 1 < g.size(); ++i)
      EXPECT_LT(metres_to(g[i], road), 5.0) << a << " - " << b << " point " << i;
  }
  // The bends: 102 on West - Mitte (with 104), 106 on Mitte - Ost.
  const auto passes = [&](const model::MetroEdge* e, geo::LonLat bend) {
    return std::any_of(e->geometry.begin(), e->geometry.end(),
                       [&](geo::LonLat p) { return geo::geodesic_distance_m(p, bend) < 5; });
  };
  EXPECT_TRUE(passes(edge_between(net, "West", "Mitte"), road[1]) &&
              passes(edge_between(net, "West", "Mitte"), road[3]));
  EXPECT_TRUE(passes(edge_between(net, "Mitte", "Ost"), road[5]));
  EXPECT_EQ(stats.gaps_repaired, 1u);  // 202 taken before 203
  EXPECT_TRUE(mentions(stats, 10, "no track ways"));
  EXPECT_FALSE(mentions(stats, 11, ""));  // route 11 is whole
}

TEST(MetroOsm, StopsWithoutANameTakeTheirStreets) {
  // Two unnamed bus stops 10 m beside a named street and one far from any: the first two take
  // the street's name (no "Stop 123" on a tourist map), the third none that would mislead.
  test::TempDir dir;
  const auto path = dir.write(
      "streets.osm",
      osm(node(101, 10.000, 50.000) + node(102, 10.010, 50.000) + node(103, 10.010, 50.010) +
          way(201, {101, 102}, tag("highway", "primary") + tag("name", "Landstrasse")) +
          way(202, {102, 103}, tag("highway", "residential")) + node(1, 10.001, 49.9999, tag("highway", "bus_stop")) +
          node(2, 10.008, 50.0001, tag("highway", "bus_stop")) + node(3, 10.011, 50.010, tag("highway", "bus_stop")) +
          relation(10, {"n1:platform", "n2:platform", "n3:platform", "w201:", "w202:"},
                   tag("type", "route") + tag("route", "bus") + tag("ref", "9"))));
  const auto net = load_metro_osm(path, {"bus"});
  std::vector<std::string> names;
  for (const auto& n : net.nodes) names.push_back(n.name);
  std::sort(names.begin(), names.end());
  ASSERT_EQ(names.size(), 3u);
  EXPECT_EQ(names[0], "Landstrasse");
  EXPECT_EQ(names[1], "Landstrasse");
  EXPECT_EQ(names[2].rfind("Stop ", 0), 0u) << names[2];  // way 202 has no name
}

TEST(MetroOsm, GapInTheTrackLeavesAStraightEdgeAndIsReported) {
  test::TempDir dir;
  const auto path = dir.write("bus.osm", bus_town());
  OsmTransitStats stats;
  const auto net = load_metro_osm(path, {"bus"}, {}, &stats);
  const auto* before = edge_between(net, "Nord 1", "Nord 2");
  const auto* across = edge_between(net, "Nord 2", "Nord 3");
  ASSERT_TRUE(before && across);
  EXPECT_GE(before->geometry.size(), 3u);  // through the bend at 112
  EXPECT_EQ(across->geometry.size(), 2u);  // straight across the gap
  EXPECT_EQ(stats.gaps, 1u);
  EXPECT_TRUE(mentions(stats, 12, "1 gap in the track, between ways 301 and 302"))
      << (stats.problems.empty() ? "" : stats.problems.back().message);
  EXPECT_TRUE(mentions(stats, 12, "Nord 2 - Nord 3 (a gap in the track)"));
  EXPECT_EQ(stats.routes_with_track, 2u);  // 11 and 12
  EXPECT_EQ(stats.track_edges, 3u);        // West - Mitte, Mitte - Ost, Nord 1 - Nord 2
  EXPECT_EQ(stats.straight_edges, 1u);
  for (const auto& p : stats.problems)
    EXPECT_EQ(p.message.rfind("relation " + std::to_string(p.relation) + " (bus ", 0), 0u) << p.message;
}

// Three more shapes of track: a roundabout mapped as one closed way (route 30, entered from the
// west, left to the east, drawn anticlockwise: through its south node, not its north one); a
// route serving both directions in one relation (31: forward_stop, backward_stop, the turn with
// role stop, its ways listed once, a stop served only on the way back); a branch the route runs
// up and back, listed once (32).
std::string track_shapes() {
  const auto bus_stop = [](const std::string& name) { return tag("highway", "bus_stop") + tag("name", name); };
  const auto bus = [](const std::string& ref) { return tag("type", "route") + tag("route", "bus") + tag("ref", ref); };
  return osm(node(401, 11.000, 48.000) + node(402, 11.004, 48.000) + node(403, 11.0045, 48.0005) +
             node(404, 11.005, 48.000) + node(405, 11.0045, 47.9995) + node(406, 11.009, 48.000) +
             node(41, 11.000, 47.9996, bus_stop("Ring West")) + node(42, 11.009, 47.9996, bus_stop("Ring Ost")) +
             way(501, {401, 402}) + way(502, {402, 405, 404, 403, 402}) + way(503, {404, 406}) +
             relation(30, {"n41:platform", "n42:platform", "w501:", "w502:", "w503:"}, bus("30")) +
             // Both ways: Hin, Mitte, Ende (the turn), then back through Zurueck (way back only) to Mitte.
             node(601, 11.000, 48.010) + node(602, 11.005, 48.012) + node(603, 11.010, 48.010) +
             node(604, 11.015, 48.012) + node(605, 11.020, 48.010) + way(701, {601, 602, 603}) +
             way(702, {603, 604, 605}) + node(61, 11.000, 48.0096, bus_stop("Hin")) +
             node(62, 11.010, 48.0096, bus_stop("Mitte")) + node(63, 11.020, 48.0096, bus_stop("Ende")) +
             node(64, 11.015, 48.0124, bus_stop("Zurueck")) + node(65, 11.010, 48.0104, bus_stop("Mitte")) +
             relation(31,
                      {"n61:forward_stop", "n62:forward_stop", "n63:stop", "n64:backward_stop", "n65:backward_stop",
                       "w701:", "w702:"},
                      bus("31")) +
             // The branch: Tal - junction 802 - up to Berg and back - Dorf.
             node(801, 11.000, 48.020) + node(802, 11.005, 48.020) + node(803, 11.006, 48.0225) +
             node(804, 11.005, 48.025) + node(805, 11.010, 48.020) + way(901, {801, 802}) + way(902, {802, 803, 804}) +
             way(903, {802, 805}) + node(81, 11.000, 48.0196, bus_stop("Tal")) +
             node(82, 11.0054, 48.025, bus_stop("Berg")) + node(83, 11.010, 48.0196, bus_stop("Dorf")) +
             relation(32, {"n81:platform", "n82:platform", "n83:platform", "w901:", "w902:", "w903:"}, bus("32")));
}

// True when some point of the edge's geometry is within `metres` of p.
bool passes(const model::MetroEdge& e, geo::LonLat p, double metres) {
  return std::any_of(e.geometry.begin(), e.geometry.end(),
                     [&](geo::LonLat q) { return geo::geodesic_distance_m(p, q) < metres; });
}

void expect_oriented(const model::MetroNetwork& net, const model::MetroEdge& e) {
  EXPECT_TRUE(same(e.geometry.front(), net.nodes[e.from].pos) && same(e.geometry.back(), net.nodes[e.to].pos))
      << net.nodes[e.from].name << " - " << net.nodes[e.to].name;
}

TEST(MetroOsm, RoundaboutsBothWaysRoutesAndBranches) {
  test::TempDir dir;
  const auto path = dir.write("shapes.osm", track_shapes());
  OsmTransitStats stats;
  const auto net = load_metro_osm(path, {"bus"}, {}, &stats);
  for (const auto& e : net.edges) expect_oriented(net, e);
  // The roundabout: round its south side, anticlockwise as drawn.
  const auto* ring = edge_between(net, "Ring West", "Ring Ost");
  ASSERT_TRUE(ring);
  EXPECT_TRUE(passes(*ring, {11.0045, 47.9995}, 5));
  EXPECT_FALSE(passes(*ring, {11.0045, 48.0005}, 30));
  // Both ways: the way back's edges follow the road too (the track reversed), Ende - Zurueck through 604's bend.
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{
           {"Hin", "Mitte"}, {"Mitte", "Ende"}, {"Ende", "Zurueck"}, {"Zurueck", "Mitte"}}) {
    const auto* e = edge_between(net, a, b);
    ASSERT_TRUE(e) << a << " - " << b;
    EXPECT_GE(e->geometry.size(), 3u) << a << " - " << b;
  }
  EXPECT_TRUE(passes(*edge_between(net, "Ende", "Zurueck"), {11.015, 48.012}, 10));
  // The branch: up to Berg along 803 and back down to the junction.
  const auto* up = edge_between(net, "Tal", "Berg");
  const auto* down = edge_between(net, "Berg", "Dorf");
  ASSERT_TRUE(up && down);
  EXPECT_TRUE(passes(*up, {11.006, 48.0225}, 5));
  EXPECT_TRUE(passes(*down, {11.006, 48.0225}, 5) && passes(*down, {11.005, 48.020}, 5));
  EXPECT_EQ(stats.track_edges, net.edges.size());
  EXPECT_EQ(stats.gaps, 0u);
  EXPECT_TRUE(stats.problems.empty()) << stats.problems.front().message;
}

TEST(MetroOsm, TrackPointsAreBounded) {
  test::TempDir dir;
  const auto path = dir.write("bus.osm", bus_town());
  ImportLimits limits;
  limits.max_osm_track_points = 10;
  try {
    load_metro_osm(path, {"bus"}, limits);
    FAIL() << "no limit";
  } catch (const LimitExceeded& e) {
    EXPECT_EQ(e.limit(), "max_osm_track_points");
  }
}

// Every edge's geometry starts and ends at its stations and stays near them; most follow the track.
void expect_track_geometry(const model::MetroNetwork& net, const OsmTransitStats& stats, double share,
                           const std::string& what) {
  EXPECT_EQ(stats.track_edges + stats.straight_edges, net.edges.size()) << what;
  EXPECT_GT(static_cast<double>(stats.track_edges), share * static_cast<double>(net.edges.size())) << what;
  std::size_t curved = 0;
  for (const auto& e : net.edges) {
    const auto a = net.nodes[e.from].pos, b = net.nodes[e.to].pos;
    ASSERT_GE(e.geometry.size(), 2u);
    EXPECT_TRUE(same(e.geometry.front(), a) && same(e.geometry.back(), b)) << what;
    const double reach = std::max(3000.0, geo::geodesic_distance_m(a, b));
    for (const auto& p : e.geometry)
      EXPECT_LE(std::min(geo::geodesic_distance_m(p, a), geo::geodesic_distance_m(p, b)), reach)
          << what << ": " << net.nodes[e.from].name << " - " << net.nodes[e.to].name;
    curved += e.geometry.size() > 2 ? 1 : 0;
  }
  EXPECT_GT(curved, 0u) << what;
}

std::string summary(const OsmTransitStats& s) {
  std::string out = std::to_string(s.routes) + " routes, " + std::to_string(s.routes_with_track) + " with track, " +
                    std::to_string(s.track_edges) + " edges with track, " + std::to_string(s.straight_edges) +
                    " straight, " + std::to_string(s.gaps_repaired) + " gaps repaired, " + std::to_string(s.gaps) +
                    " gaps, " + std::to_string(s.missing_track_members) + " ways missing, " +
                    std::to_string(s.skipped_track_members) + " left out, " + std::to_string(s.track_points) +
                    " track points";
  for (const auto& p : s.problems) out += "\n  " + p.message;
  return out;
}

TEST(MetroOsm, LiechtensteinTrainAndBuses) {
  const auto extract = test::data_file("roads/liechtenstein-latest.osm.pbf");
  OsmTransitStats stats;
  const auto train = load_metro_osm(extract, {}, {}, &stats);  // rail present: the train
  EXPECT_EQ(stats.modes, std::vector<std::string>{"train"});
  EXPECT_EQ(stats.routes, 4u);
  ASSERT_EQ(train.lines.size(), 1u);
  EXPECT_EQ(train.lines[0].label, "R2");
  EXPECT_EQ(train.edges.size() + 1, train.nodes.size());  // a line: no chord beside it
  std::set<std::string> names;
  for (const auto& n : train.nodes) names.insert(n.name);
  EXPECT_TRUE(names.count("Nendeln") && names.count("Schaanwald")) << train.nodes.size() << " stations";
  expect_track_geometry(train, stats, 0.8, "train");
  EXPECT_EQ(stats.routes_without_stops, 2u);  // the RJ, through Liechtenstein without stopping: reported
  EXPECT_TRUE(mentions(stats, 3654418, "fewer than two stops in the extract"));
  std::cout << "Liechtenstein train: " << summary(stats) << "\n";
  const auto buses = load_metro_osm(extract, {"bus"}, {}, &stats);
  EXPECT_EQ(stats.routes, 16u);
  // 14 of them serve both directions in one relation (roles forward_stop, backward_stop): all used.
  EXPECT_EQ(stats.routes_without_stops, 0u);
  EXPECT_GE(buses.lines.size(), 10u);
  EXPECT_GE(buses.nodes.size(), 100u);
  expect_track_geometry(buses, stats, 0.8, "buses");
  std::cout << "Liechtenstein buses: " << summary(stats) << "\n";
}

TEST(MetroOsm, MonacoBuses) {
  // Monaco's routes list their stops as plain node members (role "").
  const auto extract = test::data_file("roads/monaco.osm.gz");
  OsmTransitStats stats;
  const auto net = load_metro_osm(extract, {}, {}, &stats);
  EXPECT_EQ(stats.modes, std::vector<std::string>{"bus"});
  EXPECT_EQ(stats.routes, 10u);
  EXPECT_EQ(stats.routes_without_stops, 0u);
  EXPECT_EQ(net.lines.size(), 5u);  // five route masters
  EXPECT_GE(net.nodes.size(), 20u);
  expect_track_geometry(net, stats, 0.8, "Monaco");
  std::cout << "Monaco buses: " << summary(stats) << "\n";
}

}  // namespace
}  // namespace tourmap::load
