#pragma once
// A transit line graph from a GTFS feed (issue 16, part 2): a .zip file (its entries at the top
// or in one folder) or a folder holding
//   routes.txt      route_id, route_type; route_short_name, route_long_name, route_color
//   trips.txt       trip_id, route_id; shape_id
//   stops.txt       stop_id, stop_lat, stop_lon; stop_name, location_type, parent_station
//   stop_times.txt  trip_id, stop_id, stop_sequence
//   shapes.txt      (optional) shape_id, shape_pt_lat, shape_pt_lon, shape_pt_sequence
// Files are CSV (csv_stream.hpp: UTF-8 BOM, CRLF, quoted fields); columns are found by their
// header name in any order, other columns and files are ignored.
//
// Modes: the route_type of a route gives its mode: 0 tram (light_rail asks for it too),
// 1 subway, 2 train, 3 bus, 4 ferry, 5 cable_tram, 6 aerial_lift, 7 funicular, 11 trolleybus,
// 12 monorail; the extended types 100-199 and 300-399 train, 200-299 coach, 400-699 subway
// (405 monorail), 700-799 bus, 800-899 trolleybus, 900-999 tram, 1000-1099 and 1200-1299
// ferry, 1300-1399 aerial_lift, 1400-1499 funicular; others (air, taxi) none. None asked: the
// rail modes among the routes with trips (default_transit_modes, metro_osm.hpp), else bus.
//
// Lines: one per route of the modes with a trip of two stations or more: id route_id, label
// route_short_name (else route_long_name, else route_id), colour route_color ("rrggbb", lower
// case, as MetroLine keeps it). Stations: a stop joins the station at the root of its
// parent_station chain; a stop without a parent is a station of its own. Node id "s" +
// stop_id of the station, at the station's stop_lat/stop_lon (else the mean of its stops
// with coordinates), named by its stop_name (else a stop's, else the stop_id); only stations
// served by a kept trip become nodes. Edges: a trip's stations in stop_sequence order (the
// same station twice in a row once) are its pattern; the distinct patterns of a route (a
// pattern and its reverse are one) give the line's edges between consecutive stations, and
// lines on the same two stations share one edge (MetroBuilder). An edge is straight unless a
// trip of its pattern has a shape: then it follows the shape between the points nearest to its
// two stations (found in order along the shape; a station farther than 300 m from the shape
// makes the pattern straight).
//
// Streamed: stop_times.txt is read row by row (from the zip entry as it inflates) and only the
// current trip's rows are held; a trip's pattern is made when its rows end. When a trip's rows
// are spread over the file (not grouped by trip), the file is read a second time for those trips
// alone, holding their rows. Bounded by the GTFS limits (max_gtfs_*: bytes and rows of a file,
// stops, trips and routes held, stop_times rows held, shape positions), the CSV limits, the
// metro limits of the network built (max_metro_*) and max_id_bytes/max_name_bytes. Polls
// util::check_stop().
//
// Throws LoadError naming the file and row ("stop_times.txt row 1234: unknown stop_id 'X'"):
// no such feed, a required file or column missing ("feed.zip: no stops.txt", "routes.txt:
// missing column route_id"), a duplicate id, a trip of an unknown route, a stop_time of an
// unknown trip or stop, a stop of an unknown parent, a non-numeric route_type, stop_sequence or
// coordinate, coordinates out of range, a station without coordinates; and when no route of the
// modes has a trip of two stations.

#include "load/import_limits.hpp"
#include "model/metro.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace tourmap::load {

struct GtfsStats {
  std::vector<std::string> modes;      // the modes read
  std::size_t routes = 0;              // rows of routes.txt
  std::size_t routes_of_modes = 0;     // of those, of the modes read and with a trip
  std::size_t lines = 0;               // routes kept: with a trip of two stations or more
  std::size_t trips = 0;               // rows of trips.txt
  std::size_t trips_of_modes = 0;      // trips of the routes of the modes
  std::size_t stop_times = 0;          // rows of stop_times.txt
  std::size_t unsorted_trips = 0;      // trips whose rows are spread over stop_times.txt (read twice)
  std::size_t patterns = 0;            // distinct stop patterns of the kept routes (either direction)
  std::size_t stations = 0;            // stations served by them: the nodes of the network
  std::size_t shapes_used = 0;         // shapes that gave edges their geometry
  std::size_t patterns_off_shape = 0;  // patterns with a shape too far from a station: straight
};

// The mode of a GTFS route_type (basic or extended), "" for none (air, taxi, unknown types).
std::string gtfs_route_mode(int route_type);
// The modes a feed may be filtered by.
const std::vector<std::string>& gtfs_modes();

// Reads the feed at `path` (a .zip file or a folder). `modes` empty: the default above.
model::MetroNetwork load_metro_gtfs(const std::string& path, const std::vector<std::string>& modes = {},
                                    const ImportLimits& limits = {}, GtfsStats* stats = nullptr);

}  // namespace tourmap::load
