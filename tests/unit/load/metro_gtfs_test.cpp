// Transit line graphs from GTFS feeds (load/metro_gtfs.hpp): Vienna's LOOM graph written out as
// a feed (folder and zip, with and without shapes) and read back; stations from parent stations,
// stop patterns, route types, shapes; hostile and broken feeds (missing files and columns,
// unknown ids with the file and row, BOM, CRLF, quotes, unsorted stop_times, limits); the
// streamed CSV reader over odd chunks; and the published sample feed from npm.

#include "load/metro_gtfs.hpp"

#include "geo/projection.hpp"
#include "load/csv_stream.hpp"
#include "load/load_error.hpp"
#include "load/metro_load.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"
#include "zip_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

namespace tourmap::load {
namespace {

using Files = std::map<std::string, std::string>;  // file name -> text

// --- writing feeds ---

std::string write_folder(const test::TempDir& dir, const std::string& name, const Files& files) {
  for (const auto& [file, text] : files) dir.write(name + "/" + file, text);
  return dir.file(name);
}

// A zip through libzip (tests/support/zip_file.hpp), its entries under `prefix` ("" or "feed/").
using test::write_zip;

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string number(double value) {
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

// --- a network written out as GTFS ---

std::string node_key(const model::MetroNode& node) { return node.name.empty() ? node.id : node.name; }

// The edges of `line` walked into paths (from ends first): the node sequence of each.
std::vector<std::vector<std::uint32_t>> line_paths(const model::MetroNetwork& net, std::uint32_t line,
                                                   std::vector<std::vector<std::size_t>>* path_edges) {
  std::map<std::uint32_t, std::vector<std::size_t>> at;  // node -> the line's edges there
  for (std::size_t e = 0; e < net.edges.size(); ++e)
    if (std::count(net.edges[e].lines.begin(), net.edges[e].lines.end(), line)) {
      at[net.edges[e].from].push_back(e);
      at[net.edges[e].to].push_back(e);
    }
  std::set<std::size_t> used;
  const auto unused_at = [&](std::uint32_t v) {
    std::size_t n = 0;
    for (auto e : at[v]) n += used.count(e) ? 0 : 1;
    return n;
  };
  std::vector<std::vector<std::uint32_t>> paths;
  for (bool odd_first : {true, false})
    for (const auto& [start, edges] : at) {
      while (unused_at(start) > 0 && (!odd_first || unused_at(start) % 2 == 1)) {
        std::vector<std::uint32_t> path{start};
        std::vector<std::size_t> walked;
        for (std::uint32_t v = start;;) {
          auto next = std::find_if(at[v].begin(), at[v].end(), [&](std::size_t e) { return !used.count(e); });
          if (next == at[v].end()) break;
          used.insert(*next);
          walked.push_back(*next);
          v = net.edges[*next].from == v ? net.edges[*next].to : net.edges[*next].from;
          path.push_back(v);
        }
        paths.push_back(path);
        if (path_edges) path_edges->push_back(walked);
      }
    }
  return paths;
}

// One route per line (subway), two trips per path of the line (there and back); with shapes,
// the forward trip's shape is the path's track.
Files gtfs_of(const model::MetroNetwork& net, bool with_shapes) {
  Files f;
  // Columns in an unusual order, with columns the loader does not read.
  std::string stops = "stop_lat,stop_id,stop_code,stop_lon,stop_name\n";
  for (const auto& n : net.nodes)
    stops += number(n.pos.lat) + "," + csv_field(n.id) + ",," + number(n.pos.lon) + "," + csv_field(node_key(n)) + "\n";
  std::string routes = "route_id,agency_id,route_short_name,route_long_name,route_type,route_color\n";
  std::string trips = "route_id,service_id,trip_id,direction_id,shape_id\n";
  std::string stop_times = "trip_id,arrival_time,departure_time,stop_id,stop_sequence\n";
  std::string shapes = "shape_id,shape_pt_lat,shape_pt_lon,shape_pt_sequence\n";
  for (std::uint32_t l = 0; l < net.lines.size(); ++l) {
    const auto& line = net.lines[l];
    routes += csv_field(line.id) + ",wl," + csv_field(line.label) + ",,1," + line.color + "\n";
    std::vector<std::vector<std::size_t>> edges;
    const auto paths = line_paths(net, l, &edges);
    for (std::size_t p = 0; p < paths.size(); ++p) {
      const auto trip = line.id + "-" + std::to_string(p);
      const auto shape = with_shapes ? "shape-" + trip : std::string();
      trips += csv_field(line.id) + ",daily," + csv_field(trip) + ",0," + csv_field(shape) + "\n";
      trips += csv_field(line.id) + ",daily," + csv_field(trip + "-back") + ",1,\n";
      const auto& path = paths[p];
      for (std::size_t i = 0; i < path.size(); ++i) {
        const auto time = "08:" + std::string(i < 10 ? "0" : "") + std::to_string(i) + ":00";
        stop_times += csv_field(trip) + "," + time + "," + time + "," + csv_field(net.nodes[path[i]].id) + "," +
                      std::to_string(10 * i + 5) + "\n";
      }
      for (std::size_t i = 0; i < path.size(); ++i)  // back: sequence numbers 1, 2, ...
        stop_times += csv_field(trip + "-back") + ",09:00:00,09:00:00," + csv_field(net.nodes[path[path.size() - 1 - i]].id) +
                      "," + std::to_string(i + 1) + "\n";
      if (!with_shapes) continue;
      std::vector<geo::LonLat> track;
      for (std::size_t i = 0; i < edges[p].size(); ++i) {
        auto g = net.edges[edges[p][i]].geometry;
        if (net.edges[edges[p][i]].from != path[i]) std::reverse(g.begin(), g.end());
        track.insert(track.end(), g.begin() + (track.empty() ? 0 : 1), g.end());
      }
      for (std::size_t i = 0; i < track.size(); ++i)
        shapes += csv_field(shape) + "," + number(track[i].lat) + "," + number(track[i].lon) + "," + std::to_string(i) + "\n";
    }
  }
  f["stops.txt"] = stops;
  f["routes.txt"] = routes;
  f["trips.txt"] = trips;
  f["stop_times.txt"] = stop_times;
  if (with_shapes) f["shapes.txt"] = shapes;
  f["agency.txt"] = "agency_id,agency_name,agency_url,agency_timezone\nwl,Wiener Linien,https://wienerlinien.at,Europe/Vienna\n";
  return f;
}

// Edges as (name, name, line ids), names in order.
using EdgeKey = std::tuple<std::string, std::string, std::set<std::string>>;
std::set<EdgeKey> edge_keys(const model::MetroNetwork& net) {
  std::set<EdgeKey> out;
  for (const auto& e : net.edges) {
    auto a = node_key(net.nodes[e.from]), b = node_key(net.nodes[e.to]);
    if (b < a) std::swap(a, b);
    std::set<std::string> lines;
    for (auto l : e.lines) lines.insert(net.lines[l].id);
    out.insert({a, b, lines});
  }
  return out;
}

double length_m(const std::vector<geo::LonLat>& line) {
  double sum = 0;
  for (std::size_t i = 1; i < line.size(); ++i) sum += geo::geodesic_distance_m(line[i - 1], line[i]);
  return sum;
}

const model::MetroEdge* find_edge(const model::MetroNetwork& net, const std::string& a, const std::string& b) {
  for (const auto& e : net.edges) {
    const auto x = node_key(net.nodes[e.from]), y = node_key(net.nodes[e.to]);
    if ((x == a && y == b) || (x == b && y == a)) return &e;
  }
  return nullptr;
}

// The imported network holds the original's stations (by name, within 3 m), lines (id, label,
// colour) and edges (the same lines on the same two stations); with shapes, their track.
void expect_same_network(const model::MetroNetwork& original, const model::MetroNetwork& imported, bool shapes) {
  std::map<std::string, geo::LonLat> want, got;
  for (const auto& n : original.nodes) want[node_key(n)] = n.pos;
  for (const auto& n : imported.nodes) {
    EXPECT_TRUE(n.is_station()) << n.id;
    got[n.name] = n.pos;
  }
  ASSERT_EQ(got.size(), want.size());
  for (const auto& [name, pos] : want) {
    ASSERT_TRUE(got.count(name)) << name;
    EXPECT_LT(geo::geodesic_distance_m(pos, got[name]), 3.0) << name;
  }
  std::map<std::string, std::pair<std::string, std::string>> want_lines, got_lines;
  for (const auto& l : original.lines) want_lines[l.id] = {l.label, l.color};
  for (const auto& l : imported.lines) got_lines[l.id] = {l.label, l.color};
  EXPECT_EQ(got_lines, want_lines);
  EXPECT_EQ(edge_keys(imported), edge_keys(original));
  for (const auto& e : imported.edges) {
    const auto& from = imported.nodes[e.from];
    const auto& to = imported.nodes[e.to];
    ASSERT_GE(e.geometry.size(), 2u);
    EXPECT_LT(geo::geodesic_distance_m(e.geometry.front(), from.pos), 0.01) << from.name;
    EXPECT_LT(geo::geodesic_distance_m(e.geometry.back(), to.pos), 0.01) << to.name;
    const auto* o = find_edge(original, from.name, to.name);
    ASSERT_TRUE(o);
    if (!shapes) {
      EXPECT_EQ(e.geometry.size(), 2u);
      continue;
    }
    // Along the track: the same length (within 2 % and 10 m), its bends kept. The edge runs
    // from station to station, LOOM's track ends up to ~80 m beside a station (where its lines
    // fan out), and the shape near a station holds the ends of both edges there and the jump
    // between them: the length is that of the track, give or take twice those gaps.
    auto track = o->geometry;
    if (node_key(original.nodes[o->from]) != from.name) std::reverse(track.begin(), track.end());
    const double gaps = geo::geodesic_distance_m(from.pos, track.front()) + geo::geodesic_distance_m(to.pos, track.back());
    const double want_m = length_m(track), got_m = length_m(e.geometry);
    EXPECT_NEAR(got_m, want_m, std::max(10.0, 0.02 * want_m) + 2 * gaps) << from.name << " - " << to.name;
    if (o->geometry.size() > 4) {
      EXPECT_GT(e.geometry.size(), 2u) << from.name << " - " << to.name;
    }
  }
}

model::MetroNetwork vienna() { return load_metro_loom(test::data_file("metro/loom_wien.json")); }

TEST(MetroGtfs, ViennaRoundTripFolderAndZip) {
  const auto original = vienna();
  ASSERT_GT(original.edges.size(), 90u);
  const auto files = gtfs_of(original, false);
  test::TempDir dir;
  GtfsStats stats;
  const auto from_folder = load_metro_gtfs(write_folder(dir, "wien", files), {}, {}, &stats);
  expect_same_network(original, from_folder, false);
  EXPECT_EQ(stats.modes, std::vector<std::string>{"subway"});
  EXPECT_EQ(stats.routes, original.lines.size());
  EXPECT_EQ(stats.lines, original.lines.size());
  EXPECT_EQ(stats.stations, original.nodes.size());
  EXPECT_EQ(stats.trips, 2 * stats.patterns);  // there and back: one pattern
  EXPECT_EQ(stats.unsorted_trips, 0u);
  EXPECT_EQ(stats.shapes_used, 0u);

  const auto from_zip = load_metro_gtfs(write_zip(dir, "wien.zip", files), {}, {}, &stats);
  expect_same_network(original, from_zip, false);
  // Entries in a folder of the zip, as some agencies publish them.
  const auto nested = load_metro_gtfs(write_zip(dir, "wien-nested.zip", files, "gtfs-wien/"));
  expect_same_network(original, nested, false);
}

TEST(MetroGtfs, ViennaRoundTripAlongShapes) {
  const auto original = vienna();
  const auto files = gtfs_of(original, true);
  test::TempDir dir;
  GtfsStats stats;
  const auto net = load_metro_gtfs(write_zip(dir, "wien.zip", files), {"subway"}, {}, &stats);
  expect_same_network(original, net, true);
  EXPECT_EQ(stats.shapes_used, stats.patterns);
  EXPECT_EQ(stats.patterns_off_shape, 0u);
  const auto folder = load_metro_gtfs(write_folder(dir, "wien", files), {"subway"});
  expect_same_network(original, folder, true);
}

// --- small feeds ---

// Tram T1: Markt - Rathaus (a station of two platforms) - Bahnhof, there (t1) and back (t2, by the
// other platform); bus B5: Markt - Bahnhof.
Files tram_town() {
  return {
      {"routes.txt", "route_id,route_short_name,route_long_name,route_type,route_color\n"
                     "T1,1,Tram One,0,E2001A\n"
                     "B5,,Bus Five,3,\n"},
      {"trips.txt", "route_id,service_id,trip_id,shape_id\nT1,d,t1,\nT1,d,t2,\nB5,d,b1,\n"},
      {"stops.txt", "stop_id,stop_name,stop_lat,stop_lon,location_type,parent_station\n"
                    "M,Markt,50.0,10.0,,\n"
                    "R,Rathaus,50.0,10.01,1,\n"
                    "R1,Rathaus Gleis 1,50.0001,10.0101,0,R\n"
                    "R2,Rathaus Gleis 2,49.9999,10.0099,0,R\n"
                    "B,Bahnhof,50.0,10.02,,\n"},
      {"stop_times.txt", "trip_id,arrival_time,departure_time,stop_id,stop_sequence\n"
                         "t1,08:00:00,08:00:00,M,1\n"
                         "t1,08:02:00,08:02:00,R1,2\n"
                         "t1,08:04:00,08:04:00,B,3\n"
                         "t2,09:00:00,09:00:00,B,1\n"
                         "t2,09:02:00,09:02:00,R2,2\n"
                         "t2,09:04:00,09:04:00,M,3\n"
                         "b1,10:00:00,10:00:00,M,1\n"
                         "b1,10:05:00,10:05:00,B,2\n"}};
}

model::MetroNetwork load_files(const Files& files, const std::vector<std::string>& modes = {},
                               const ImportLimits& limits = {}, GtfsStats* stats = nullptr) {
  test::TempDir dir;
  return load_metro_gtfs(write_folder(dir, "town", files), modes, limits, stats);
}

// The message of the LoadError the feed raises ("" when it loads).
std::string error_of(const Files& files, const std::vector<std::string>& modes = {}, const ImportLimits& limits = {}) {
  try {
    load_files(files, modes, limits);
  } catch (const LimitExceeded& e) {
    return "limit " + e.limit() + ": " + e.what();
  } catch (const LoadError& e) {
    return e.what();
  }
  return "";
}

std::string error_of_path(const std::string& path, const ImportLimits& limits) {
  try {
    load_metro_gtfs(path, {}, limits);
  } catch (const LimitExceeded& e) {
    return "limit " + e.limit() + ": " + e.what();
  } catch (const LoadError& e) {
    return e.what();
  }
  return "";
}

std::set<std::pair<std::string, std::string>> edges_by_name(const model::MetroNetwork& net) {
  std::set<std::pair<std::string, std::string>> out;
  for (const auto& e : net.edges) {
    auto a = net.nodes[e.from].name, b = net.nodes[e.to].name;
    out.insert(a < b ? std::pair{a, b} : std::pair{b, a});
  }
  return out;
}

const std::set<std::pair<std::string, std::string>> kTramEdges = {{"Markt", "Rathaus"}, {"Bahnhof", "Rathaus"}};

TEST(MetroGtfs, ParentStationsMergeAndBothDirectionsAreOnePattern) {
  GtfsStats stats;
  const auto net = load_files(tram_town(), {}, {}, &stats);
  EXPECT_EQ(stats.modes, std::vector<std::string>{"tram"});  // the rail mode present
  EXPECT_EQ(stats.routes, 2u);
  EXPECT_EQ(stats.routes_of_modes, 1u);
  EXPECT_EQ(stats.trips, 3u);
  EXPECT_EQ(stats.trips_of_modes, 2u);
  EXPECT_EQ(stats.stop_times, 8u);
  EXPECT_EQ(stats.patterns, 1u);
  EXPECT_EQ(stats.stations, 3u);
  ASSERT_EQ(net.lines.size(), 1u);
  EXPECT_EQ(net.lines[0].id, "T1");
  EXPECT_EQ(net.lines[0].label, "1");
  EXPECT_EQ(net.lines[0].color, "e2001a");
  ASSERT_EQ(net.nodes.size(), 3u);
  std::map<std::string, const model::MetroNode*> by_id;
  for (const auto& n : net.nodes) by_id[n.id] = &n;
  ASSERT_TRUE(by_id.count("sR"));
  EXPECT_EQ(by_id["sR"]->name, "Rathaus");
  EXPECT_EQ(by_id["sR"]->station_id, "sR");
  EXPECT_DOUBLE_EQ(by_id["sR"]->pos.lon, 10.01);  // the station's own position
  EXPECT_EQ(edges_by_name(net), kTramEdges);
  for (const auto& e : net.edges) EXPECT_EQ(e.geometry.size(), 2u);  // no shapes: straight

  // The bus: label from the long name; a station without coordinates sits at its platforms' mean.
  auto files = tram_town();
  files["stops.txt"] = "stop_id,stop_name,stop_lat,stop_lon,location_type,parent_station\n"
                       "M,Markt,50.0,10.0,,\nR,Rathaus,,,1,\nR1,,50.0002,10.0102,0,R\nR2,,49.9998,10.0098,0,R\n"
                       "B,Bahnhof,50.0,10.02,,\n";
  const auto both = load_files(files, {"tram", "bus"}, {}, &stats);
  EXPECT_EQ(stats.lines, 2u);
  EXPECT_EQ(both.lines[1].label, "Bus Five");
  EXPECT_EQ(both.lines[1].color, "");
  for (const auto& n : both.nodes)
    if (n.id == "sR") {
      EXPECT_NEAR(n.pos.lon, 10.01, 1e-9);
      EXPECT_NEAR(n.pos.lat, 50.0, 1e-9);
    }
  EXPECT_EQ(edges_by_name(both).size(), 3u);  // Markt - Bahnhof by bus too
}

TEST(MetroGtfs, PatternsOfARoute) {
  auto files = tram_town();
  // A short working (Markt - Rathaus), a trip of one station, a trip along the platforms of one
  // station and on: the pattern Markt - Rathaus is new, the others add nothing.
  files["trips.txt"] += "T1,d,t3,\nT1,d,t4,\nT1,d,t5,\n";
  files["stop_times.txt"] += "t3,11:00:00,11:00:00,M,1\nt3,11:02:00,11:02:00,R1,2\n"
                             "t4,11:00:00,11:00:00,B,1\n"
                             "t5,12:00:00,12:00:00,R1,1\nt5,12:01:00,12:01:00,R2,2\nt5,12:03:00,12:03:00,B,3\n";
  GtfsStats stats;
  const auto net = load_files(files, {}, {}, &stats);
  EXPECT_EQ(stats.patterns, 3u);  // M-R-B, M-R, R-B
  EXPECT_EQ(edges_by_name(net), kTramEdges);
  EXPECT_EQ(net.edges.size(), 2u);
}

TEST(MetroGtfs, RouteTypesAndModes) {
  EXPECT_EQ(gtfs_route_mode(0), "tram");
  EXPECT_EQ(gtfs_route_mode(1), "subway");
  EXPECT_EQ(gtfs_route_mode(2), "train");
  EXPECT_EQ(gtfs_route_mode(3), "bus");
  EXPECT_EQ(gtfs_route_mode(4), "ferry");
  EXPECT_EQ(gtfs_route_mode(5), "cable_tram");
  EXPECT_EQ(gtfs_route_mode(6), "aerial_lift");
  EXPECT_EQ(gtfs_route_mode(7), "funicular");
  EXPECT_EQ(gtfs_route_mode(11), "trolleybus");
  EXPECT_EQ(gtfs_route_mode(12), "monorail");
  EXPECT_EQ(gtfs_route_mode(109), "train");
  EXPECT_EQ(gtfs_route_mode(200), "coach");
  EXPECT_EQ(gtfs_route_mode(401), "subway");
  EXPECT_EQ(gtfs_route_mode(405), "monorail");
  EXPECT_EQ(gtfs_route_mode(715), "bus");
  EXPECT_EQ(gtfs_route_mode(800), "trolleybus");
  EXPECT_EQ(gtfs_route_mode(900), "tram");
  EXPECT_EQ(gtfs_route_mode(1000), "ferry");
  EXPECT_EQ(gtfs_route_mode(1200), "ferry");
  EXPECT_EQ(gtfs_route_mode(1300), "aerial_lift");
  EXPECT_EQ(gtfs_route_mode(1400), "funicular");
  EXPECT_EQ(gtfs_route_mode(1100), "");  // air
  EXPECT_EQ(gtfs_route_mode(1500), "");  // taxi
  EXPECT_EQ(gtfs_route_mode(9), "");

  // One route per type, each a trip between two of its own stations.
  const std::vector<std::pair<std::string, int>> types = {{"U1", 1}, {"S1", 109}, {"B1", 3}, {"B2", 700}, {"F1", 4}, {"X1", 1500}};
  Files files;
  files["routes.txt"] = "route_id,route_type,route_short_name\n";
  files["trips.txt"] = "trip_id,route_id\n";
  files["stops.txt"] = "stop_id,stop_lat,stop_lon,stop_name\n";
  files["stop_times.txt"] = "trip_id,stop_id,stop_sequence\n";
  for (std::size_t i = 0; i < types.size(); ++i) {
    const auto& [id, type] = types[i];
    files["routes.txt"] += id + "," + std::to_string(type) + "," + id + "\n";
    files["trips.txt"] += "t" + id + "," + id + "\n";
    for (int s = 0; s < 2; ++s) {
      const auto stop = id + "-" + std::to_string(s);
      files["stops.txt"] += stop + ",48." + std::to_string(i) + ",16." + std::to_string(s) + "," + stop + "\n";
      files["stop_times.txt"] += "t" + id + "," + stop + "," + std::to_string(s) + "\n";
    }
  }
  const auto line_ids = [](const model::MetroNetwork& net) {
    std::set<std::string> out;
    for (const auto& l : net.lines) out.insert(l.id);
    return out;
  };
  GtfsStats stats;
  EXPECT_EQ(line_ids(load_files(files, {}, {}, &stats)), (std::set<std::string>{"U1", "S1"}));  // the rail present
  EXPECT_EQ(stats.modes, (std::vector<std::string>{"subway", "train"}));
  EXPECT_EQ(line_ids(load_files(files, {"bus"})), (std::set<std::string>{"B1", "B2"}));
  EXPECT_EQ(line_ids(load_files(files, {"ferry", "subway"})), (std::set<std::string>{"U1", "F1"}));
  EXPECT_EQ(line_ids(load_files(tram_town(), {"light_rail"})), std::set<std::string>{"T1"});  // type 0
  // No rail at all: the buses.
  files["routes.txt"] = "route_id,route_type,route_short_name\nU1,3,U1\nS1,3,S1\nB1,3,B1\nB2,700,B2\nF1,4,F1\nX1,1500,X1\n";
  EXPECT_EQ(line_ids(load_files(files, {}, {}, &stats)), (std::set<std::string>{"U1", "S1", "B1", "B2"}));
  EXPECT_EQ(stats.modes, std::vector<std::string>{"bus"});

  const auto none = error_of(files, {"aerial_lift"});
  EXPECT_NE(none.find("town: no route of the modes aerial_lift has a trip of two stations"), std::string::npos) << none;
  const auto unknown = error_of(files, {"hovercraft"});
  EXPECT_NE(unknown.find("unknown transit mode 'hovercraft'"), std::string::npos) << unknown;
}

TEST(MetroGtfs, EdgesFollowShapes) {
  auto files = tram_town();
  // t2 (Bahnhof to Markt) has a shape bulging north between the stations, as the track does.
  files["trips.txt"] = "route_id,service_id,trip_id,shape_id\nT1,d,t1,\nT1,d,t2,bulge\nB5,d,b1,far\n";
  files["shapes.txt"] = "shape_id,shape_pt_sequence,shape_pt_lat,shape_pt_lon\n"
                        "bulge,5,50.0,10.0\n"  // out of order: sorted by sequence
                        "bulge,1,50.0,10.02\n"
                        "bulge,2,50.002,10.015\n"
                        "bulge,3,50.0,10.01\n"
                        "bulge,4,50.002,10.005\n"
                        "far,1,51.0,10.0\nfar,2,51.0,10.02\n"
                        "unused,1,0,0\nunused,2,0,1\n";
  GtfsStats stats;
  auto net = load_files(files, {"tram", "bus"}, {}, &stats);
  EXPECT_EQ(stats.shapes_used, 1u);
  EXPECT_EQ(stats.patterns_off_shape, 1u);  // the bus's shape is 111 km away: straight
  ASSERT_EQ(net.edges.size(), 3u);
  for (const auto& e : net.edges) {
    const auto& a = net.nodes[e.from];
    const auto& b = net.nodes[e.to];
    EXPECT_DOUBLE_EQ(e.geometry.front().lon, a.pos.lon);
    EXPECT_DOUBLE_EQ(e.geometry.back().lon, b.pos.lon);
    if (std::set<std::string>{a.name, b.name} == std::set<std::string>{"Bahnhof", "Markt"}) {
      EXPECT_EQ(e.geometry.size(), 2u) << "the bus: straight";
      continue;
    }
    ASSERT_EQ(e.geometry.size(), 3u) << a.name << " - " << b.name;
    EXPECT_NEAR(e.geometry[1].lat, 50.002, 1e-9);  // the bulge's point between the two stations
    const double lon = e.geometry[1].lon;
    EXPECT_TRUE(std::abs(lon - 10.005) < 1e-9 || std::abs(lon - 10.015) < 1e-9) << lon;
  }
  // Without shapes.txt the shape ids name nothing: straight.
  files.erase("shapes.txt");
  net = load_files(files, {"tram"}, {}, &stats);
  EXPECT_EQ(stats.shapes_used, 0u);
  for (const auto& e : net.edges) EXPECT_EQ(e.geometry.size(), 2u);
}

// --- broken and hostile feeds ---

TEST(MetroGtfs, MissingFilesAndColumns) {
  for (const auto* file : {"stops.txt", "routes.txt", "trips.txt", "stop_times.txt"}) {
    auto files = tram_town();
    files.erase(file);
    EXPECT_EQ(error_of(files), std::string("town: no ") + file);
  }
  auto files = tram_town();
  files["routes.txt"] = "id,route_short_name,route_type\nT1,1,0\n";
  EXPECT_EQ(error_of(files), "routes.txt: missing column route_id");
  files = tram_town();
  files["stop_times.txt"] = "trip_id,stop_id,arrival_time\nt1,M,08:00:00\n";
  EXPECT_EQ(error_of(files), "stop_times.txt: missing column stop_sequence");
  files = tram_town();
  files["stops.txt"] = "";
  EXPECT_EQ(error_of(files), "stops.txt: empty file (no header)");

  test::TempDir dir;
  EXPECT_THROW(load_metro_gtfs(dir.file("nothing.zip")), LoadError);
  const auto junk = dir.write("junk.zip", "this is not a zip file");
  try {
    load_metro_gtfs(junk);
    FAIL();
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("junk.zip: not a GTFS zip file or folder"), std::string::npos) << e.what();
  }
  auto zipped = tram_town();
  zipped.erase("stops.txt");
  EXPECT_EQ(std::string([&] {
              try {
                load_metro_gtfs(write_zip(dir, "feed.zip", zipped));
              } catch (const LoadError& e) {
                return std::string(e.what());
              }
              return std::string();
            }()),
            "feed.zip: no stops.txt");
}

TEST(MetroGtfs, UnknownIdsNameTheFileAndRow) {
  auto files = tram_town();
  files["stop_times.txt"] += "t1,08:06:00,08:06:00,X,4\n";
  EXPECT_EQ(error_of(files), "stop_times.txt row 10: unknown stop_id 'X'");
  files = tram_town();
  files["stop_times.txt"] += "t9,08:06:00,08:06:00,M,4\n";
  EXPECT_EQ(error_of(files), "stop_times.txt row 10: unknown trip_id 't9'");
  files = tram_town();
  files["trips.txt"] += "T7,d,t7,\n";
  EXPECT_EQ(error_of(files), "trips.txt row 5: unknown route_id 'T7'");
  files = tram_town();
  files["stops.txt"] += "Q1,Quai,50.1,10.1,0,Q\n";
  EXPECT_EQ(error_of(files), "stops.txt row 7: unknown parent_station 'Q'");
  files = tram_town();
  files["stops.txt"] += "L1,Loop,50.1,10.1,0,L2\nL2,Loop,50.1,10.1,0,L1\n";
  EXPECT_NE(error_of(files).find("loops"), std::string::npos);
  files = tram_town();
  files["stops.txt"] += "M,Markt again,50.1,10.1,,\n";
  EXPECT_EQ(error_of(files), "stops.txt row 7: duplicate stop_id 'M'");
  files = tram_town();
  files["trips.txt"] += "T1,d,t1,\n";
  EXPECT_EQ(error_of(files), "trips.txt row 5: duplicate trip_id 't1'");
  // Even in a trip of a mode not read: every row is checked.
  files = tram_town();
  files["stop_times.txt"] += "b1,10:07:00,10:07:00,Y,3\n";
  EXPECT_EQ(error_of(files), "stop_times.txt row 10: unknown stop_id 'Y'");
  // A long id is clipped in the message.
  files = tram_town();
  files["stop_times.txt"] += "t1,08:06:00,08:06:00," + std::string(200, 'z') + ",4\n";
  EXPECT_EQ(error_of(files), "stop_times.txt row 10: unknown stop_id '" + std::string(64, 'z') + "...'");
}

TEST(MetroGtfs, BadValues) {
  auto files = tram_town();
  files["stop_times.txt"] += "t1,08:06:00,08:06:00,B,fourth\n";
  EXPECT_EQ(error_of(files), "stop_times.txt row 10: stop_sequence is not a non-negative integer: 'fourth'");
  files = tram_town();
  files["stop_times.txt"] += "t1,08:06:00,08:06:00,B,-4\n";
  EXPECT_NE(error_of(files).find("row 10: stop_sequence is not a non-negative integer"), std::string::npos);
  files = tram_town();
  files["stops.txt"] += "N,North,95.0,10.0,,\n";
  EXPECT_EQ(error_of(files), "stops.txt row 7: coordinates out of range: stop_lat 95.0, stop_lon 10.0");
  files = tram_town();
  files["stops.txt"] += "N,North,fifty,10.0,,\n";
  EXPECT_NE(error_of(files).find("stops.txt row 7: column 'stop_lat' is not a number"), std::string::npos);
  files = tram_town();
  files["routes.txt"] += "T9,9,,tram,\n";
  EXPECT_EQ(error_of(files), "routes.txt row 4: route_type is not an integer: 'tram'");
  files = tram_town();
  files["stop_times.txt"] += "t1,08:06:00,B,4\n";
  EXPECT_EQ(error_of(files), "stop_times.txt row 10: expected 5 fields, found 4");
  files = tram_town();
  files["stops.txt"] += "Q,\"Quai,50.1,10.1,,\n";
  EXPECT_NE(error_of(files).find("stops.txt row 7: unterminated quoted field"), std::string::npos);
  // A served station without any coordinates.
  files = tram_town();
  files["stops.txt"] = "stop_id,stop_name,stop_lat,stop_lon,location_type,parent_station\n"
                       "M,Markt,50.0,10.0,,\nR,Rathaus,,,1,\nR1,,,,0,R\nR2,,,,0,R\nB,Bahnhof,50.0,10.02,,\n";
  EXPECT_EQ(error_of(files), "stops.txt station 'R': no coordinates (nor any of its stops)");
  // No trip of two stations.
  files = tram_town();
  files["stop_times.txt"] = "trip_id,stop_id,stop_sequence\nt1,M,1\nt2,R1,1\nt2,R2,2\n";
  EXPECT_EQ(error_of(files), "town: no route of the modes tram has a trip of two stations (1 routes, 2 trips of those modes)");
}

// BOM, CRLF, quoted fields with commas, doubled quotes and line breaks: the same network.
TEST(MetroGtfs, BomCrlfAndQuotes) {
  auto files = tram_town();
  for (auto& [name, text] : files) {
    std::string crlf = "\xEF\xBB\xBF";
    for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    text = crlf;
  }
  files["stops.txt"] = "\xEF\xBB\xBF\"stop_id\",stop_name,stop_lat,stop_lon,location_type,parent_station\r\n"
                       "\"M\",\"Markt, \"\"Alter\"\" Platz\",50.0,10.0,,\r\n"
                       "R,\"Rathaus\r\n(Gleise 1-2)\",\"50.0\",\"10.01\",1,\r\n"
                       "\r\n"  // a blank line
                       "R1,,50.0001,10.0101,0,\"R\"\r\n"
                       "R2,,49.9999,10.0099,0,R\r\n"
                       "B,Bahnhof,50.0,10.02,,";  // no line break at the end
  GtfsStats stats;
  const auto net = load_files(files, {}, {}, &stats);
  std::set<std::string> names;
  for (const auto& n : net.nodes) names.insert(n.name);
  EXPECT_EQ(names, (std::set<std::string>{"Markt, \"Alter\" Platz", "Rathaus\r\n(Gleise 1-2)", "Bahnhof"}));
  EXPECT_EQ(net.edges.size(), 2u);
  EXPECT_EQ(net.lines.at(0).color, "e2001a");
  EXPECT_EQ(stats.stop_times, 8u);
  // Rows are still counted by record (the header is row 1) with CRLF.
  files["stop_times.txt"] += "\r\nt1,08:06:00,08:06:00,X,4\r\n";
  EXPECT_EQ(error_of(files), "stop_times.txt row 11: unknown stop_id 'X'");  // the blank line is row 10
}

TEST(MetroGtfs, UnsortedStopTimes) {
  auto files = tram_town();
  // The rows of the trips interleaved, and out of sequence within each trip.
  files["stop_times.txt"] = "trip_id,arrival_time,departure_time,stop_id,stop_sequence\n"
                            "t1,08:04:00,08:04:00,B,3\n"
                            "t2,09:02:00,09:02:00,R2,2\n"
                            "b1,10:00:00,10:00:00,M,1\n"
                            "t1,08:00:00,08:00:00,M,1\n"
                            "t2,09:00:00,09:00:00,B,1\n"
                            "b1,10:05:00,10:05:00,B,2\n"
                            "t2,09:04:00,09:04:00,M,3\n"
                            "t1,08:02:00,08:02:00,R1,2\n";
  for (const auto& ext : {"", ".zip"}) {
    test::TempDir dir;
    const auto path = std::string(ext).empty() ? write_folder(dir, "town", files) : write_zip(dir, "town.zip", files);
    GtfsStats stats;
    const auto net = load_metro_gtfs(path, {"tram", "bus"}, {}, &stats);
    EXPECT_EQ(stats.unsorted_trips, 3u);
    EXPECT_EQ(stats.patterns, 2u);
    EXPECT_EQ(edges_by_name(net), (std::set<std::pair<std::string, std::string>>{
                                      {"Markt", "Rathaus"}, {"Bahnhof", "Rathaus"}, {"Bahnhof", "Markt"}}));
  }
  // Within a trip's rows, the order of stop_sequence decides (a sorted file, rows reversed).
  auto reversed = tram_town();
  reversed["stop_times.txt"] = "trip_id,stop_id,stop_sequence\nt1,B,30\nt1,R1,20\nt1,M,10\n";
  GtfsStats stats;
  const auto net = load_files(reversed, {}, {}, &stats);
  EXPECT_EQ(stats.unsorted_trips, 0u);
  EXPECT_EQ(edges_by_name(net), kTramEdges);
}

TEST(MetroGtfs, LimitsExceeded) {
  const auto limited = [](auto set) {
    ImportLimits limits;
    set(limits);
    return limits;
  };
  const auto files = tram_town();
  EXPECT_EQ(error_of(files, {}, limited([](ImportLimits& l) { l.max_gtfs_stops = 2; })),
            "limit max_gtfs_stops: stops.txt row 4: more than 2 stops (limit max_gtfs_stops = 2)");
  EXPECT_EQ(error_of(files, {}, limited([](ImportLimits& l) { l.max_gtfs_trips = 2; })),
            "limit max_gtfs_trips: trips.txt row 4: more than 2 trips (limit max_gtfs_trips = 2)");
  EXPECT_EQ(error_of(files, {}, limited([](ImportLimits& l) { l.max_gtfs_rows = 6; })),
            "limit max_gtfs_rows: stop_times.txt: more than 6 rows (limit max_gtfs_rows = 6)");
  const auto bytes = error_of(files, {}, limited([](ImportLimits& l) { l.max_gtfs_file_bytes = 150; }));
  EXPECT_EQ(bytes.rfind("limit max_gtfs_file_bytes: stops.txt: more than 150 bytes", 0), 0u) << bytes;
  // stop_times rows held: the pattern kept (3 stations) and the trip being read (3 rows), so
  // a limit of 5 stops at the second trip's third row.
  const auto held = error_of(files, {}, limited([](ImportLimits& l) { l.max_gtfs_buffered_stop_times = 5; }));
  EXPECT_EQ(held.rfind("limit max_gtfs_buffered_stop_times: stop_times.txt row 7", 0), 0u) << held;
  EXPECT_EQ(error_of(files, {}, limited([](ImportLimits& l) { l.max_gtfs_buffered_stop_times = 6; })), "");
  auto shaped = tram_town();
  shaped["trips.txt"] = "route_id,trip_id,shape_id\nT1,t1,s\nT1,t2,\nB5,b1,\n";
  shaped["shapes.txt"] = "shape_id,shape_pt_sequence,shape_pt_lat,shape_pt_lon\ns,1,50,10\ns,2,50,10.01\ns,3,50,10.02\n";
  EXPECT_EQ(error_of(shaped, {}, limited([](ImportLimits& l) { l.max_gtfs_shape_points = 2; })),
            "limit max_gtfs_shape_points: shapes.txt row 4: more than 2 shape positions held (limit max_gtfs_shape_points = 2)");
  EXPECT_EQ(error_of(shaped, {}, limited([](ImportLimits& l) { l.max_csv_field_bytes = 6; })).rfind(
                "limit max_csv_field_bytes: routes.txt row 1", 0),
            0u);
  // The network's own limits apply too.
  EXPECT_EQ(error_of(files, {}, limited([](ImportLimits& l) { l.max_metro_nodes = 2; })).rfind("limit max_metro_nodes", 0), 0u);
  // A zip bomb: 8 MB of line breaks in stop_times.txt, a few KB zipped, stops at the byte limit,
  // or at the row limit (blank lines count).
  test::TempDir dir;
  auto bomb = tram_town();
  bomb["stop_times.txt"] += std::string(8 << 20, '\n');
  const auto zip = write_zip(dir, "bomb.zip", bomb);
  EXPECT_LT(std::filesystem::file_size(zip), 100'000u);
  EXPECT_EQ(error_of_path(zip, limited([](ImportLimits& l) { l.max_gtfs_file_bytes = 1 << 20; })).rfind(
                "limit max_gtfs_file_bytes: stop_times.txt: more than 1048576 bytes", 0),
            0u);
  EXPECT_EQ(error_of_path(zip, limited([](ImportLimits& l) { l.max_gtfs_rows = 1'000'000; })),
            "limit max_gtfs_rows: stop_times.txt: more than 1000000 rows (limit max_gtfs_rows = 1000000)");
}

// --- the streamed CSV reader ---

// Hands out the text a few bytes at a time, so records, quotes, CRLF and the BOM straddle reads.
class TrickleSource final : public ByteSource {
 public:
  TrickleSource(std::string text, std::size_t step) : text_(std::move(text)), step_(step) {}
  std::size_t read(char* buffer, std::size_t size) override {
    const std::size_t n = std::min({size, step_, text_.size() - pos_});
    std::copy_n(text_.data() + pos_, n, buffer);
    pos_ += n;
    return n;
  }

 private:
  std::string text_;
  std::size_t step_, pos_ = 0;
};

TEST(MetroGtfs, CsvStreamOverSmallReads) {
  const std::string text = "\xEF\xBB\xBF id ,\"name\",x\r\n1,\"a, \"\"b\"\"\r\nc\",\r\n\r\n2,plain,\"\"\r\n3,end,z";
  for (std::size_t step : {1, 2, 3, 5, 64 * 1024}) {
    TrickleSource source(text, step);
    CsvStream csv(source, "t.csv", {});
    ASSERT_EQ(csv.header().size(), 3u);
    EXPECT_EQ(csv.column("id"), 0u);  // spaces around header names ignored, the BOM dropped
    EXPECT_EQ(csv.column("NAME"), 1u);
    EXPECT_FALSE(csv.find_column("nothing"));
    std::vector<std::vector<std::string>> rows;
    std::vector<std::size_t> numbers;
    while (csv.next()) {
      rows.push_back({std::string(csv.field(0)), std::string(csv.field(1)), std::string(csv.field(2))});
      numbers.push_back(csv.row());
    }
    EXPECT_EQ(rows, (std::vector<std::vector<std::string>>{{"1", "a, \"b\"\r\nc", ""}, {"2", "plain", ""}, {"3", "end", "z"}}))
        << step;
    EXPECT_EQ(numbers, (std::vector<std::size_t>{2, 4, 5}));  // the blank line is row 3
    EXPECT_EQ(csv.rows_read(), 3u);
  }
  // Limits of the stream as a whole and of a record.
  TrickleSource rows("a\n1\n2\n3\n", 2);
  CsvStream csv(rows, "r.csv", {}, {UINT64_MAX, "max_b", 3, "max_r"});
  EXPECT_TRUE(csv.next());
  EXPECT_TRUE(csv.next());
  try {
    csv.next();
    FAIL();
  } catch (const LimitExceeded& e) {
    EXPECT_EQ(e.limit(), "max_r");
    EXPECT_STREQ(e.what(), "r.csv: more than 3 rows (limit max_r = 3)");
  }
  ImportLimits narrow;
  narrow.max_csv_fields = 2;
  TrickleSource wide("a,b\n1,2,3\n", 1);
  CsvStream w(wide, "w.csv", narrow);
  try {
    w.next();
    FAIL();
  } catch (const LimitExceeded& e) {
    EXPECT_EQ(e.limit(), "max_csv_fields");
    EXPECT_EQ(e.where(), "w.csv row 2");
  }
}

// --- the published sample feed (npm: sample-gtfs-feed, a devDependency of web/) ---

std::string sample_feed_dir() { return std::string(TOURMAP_SOURCE_DIR) + "/web/node_modules/sample-gtfs-feed"; }

TEST(MetroGtfs, PublishedSampleFeed) {
  const auto dir = sample_feed_dir();
  // scripts/setup runs `npm ci` in web/, which installs it: missing means a broken setup, not a skip.
  ASSERT_TRUE(std::filesystem::is_directory(dir + "/gtfs"))
      << dir << "/gtfs is missing: run `npm ci` in web/ (scripts/setup does) for the sample-gtfs-feed package";
  for (const auto& path : {dir + "/gtfs", dir + "/gtfs.zip"}) {
    SCOPED_TRACE(path);
    GtfsStats stats;
    const auto net = load_metro_gtfs(path, {}, {}, &stats);
    // Bus A and trams B, C, D: the trams by default; the airport's platforms join the airport.
    EXPECT_EQ(stats.modes, std::vector<std::string>{"tram"});
    EXPECT_EQ(stats.routes, 4u);
    EXPECT_EQ(stats.routes_of_modes, 3u);
    EXPECT_EQ(stats.trips, 10u);
    EXPECT_EQ(stats.trips_of_modes, 8u);
    EXPECT_EQ(stats.stop_times, 29u);
    EXPECT_EQ(stats.patterns, 5u);  // B once; C airport-center, airport-museum-airport-center, airport-museum-center; D
    EXPECT_EQ(stats.lines, 3u);
    std::map<std::string, std::string> labels;
    for (const auto& l : net.lines) labels[l.id] = l.label + " " + l.color;
    EXPECT_EQ(labels, (std::map<std::string, std::string>{{"B", "Babbage ff0000"}, {"C", "Cerf "}, {"D", "DST "}}));
    std::set<std::string> ids;
    for (const auto& n : net.nodes) ids.insert(n.id);
    EXPECT_EQ(ids, (std::set<std::string>{"sairport", "slake", "scenter", "smuseum"}));
    for (const auto& n : net.nodes)
      if (n.id == "sairport") {
        EXPECT_EQ(n.name, "International Airport (ABC)");
        EXPECT_DOUBLE_EQ(n.pos.lat, 52.365);
      }
    EXPECT_EQ(edges_by_name(net).size(), 5u);
    for (const auto& e : net.edges)
      if (std::set<std::string>{net.nodes[e.from].id, net.nodes[e.to].id} == std::set<std::string>{"sairport", "scenter"}) {
        EXPECT_EQ(e.lines.size(), 2u);  // C and D
      }

    const auto bus = load_metro_gtfs(path, {"bus"}, {}, &stats);
    EXPECT_EQ(bus.lines.size(), 1u);
    EXPECT_EQ(stats.patterns, 1u);  // there and back
    EXPECT_EQ(stats.shapes_used + stats.patterns_off_shape, 1u);
  }
}

}  // namespace
}  // namespace tourmap::load
