// Transit line graphs from OSM route relations (load/metro_osm.hpp): lines from route masters
// (or mode and ref), stations from stop areas and names, the order of stop positions, modes,
// and Liechtenstein's extract.

#include "load/metro_osm.hpp"
#include "load/load_error.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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
  const auto buses = load_metro_osm(extract, {"bus"}, {}, &stats);
  EXPECT_EQ(stats.routes, 16u);
  EXPECT_GE(buses.lines.size(), 4u);
  EXPECT_GE(buses.nodes.size(), 20u);
  EXPECT_GT(stats.routes_without_stops, 0u);  // routes leaving the extract: reported
}

}  // namespace
}  // namespace tourmap::load
