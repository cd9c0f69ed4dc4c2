#pragma once
// A transit line graph from the route relations of an OSM extract (issue 16, part 1, first
// step), through libosmium in two passes over the file (decompressed and bounded once,
// osm_input.hpp):
//  1. relations: routes (type=route, route=<mode>) of the modes asked for, their route masters
//     (type=route_master: one line for the routes of both directions), stop areas
//     (public_transport=stop_area);
//  2. nodes and ways: the positions and names of the routes' stop and platform members (a
//     platform way at its nodes' mean).
// Modes: subway, light_rail, tram, train, bus, ferry (also monorail, funicular, trolleybus);
// none asked: the rail modes present (subway, light_rail, tram, train, monorail, funicular),
// else bus.
//
// Lines: one per route master (else per mode and ref, else per route), id "r<osm id>", label
// ref (else name), colour colour=#rrggbb of the master or a route. Stations: the stops of one
// stop area are one station; other stops of one name (case-insensitive, over two characters:
// "1" names a platform's track) within 400 m of each other are one station; a stop without
// such a name joins the nearest station within 150 m, else is a station of its own. Station
// id "s" and its first stop's "n<node id>" or "w<way id>", at the mean of its stops. A route's stations in the order of its stop positions
// (role stop*; of its platforms, role platform*, where fewer than two stop positions are in the
// extract), the same station twice in a row once, give its line's edges; lines on the same two
// stations share one edge; an edge whose lines also run through the stations along it (one
// direction listing fewer stops, an express) is dropped. Edges are straight (track geometry from the member ways, and the
// topo step that collapses parallel track, come next).
//
// Routes that cannot be used are reported in the stats, not dropped silently: fewer than two
// stops in the extract. Bounded by the OSM limits (max_osm_*), the metro limits of the
// network built (max_metro_*, metro_builder.hpp) and max_name_bytes. Polls util::check_stop().
// Throws LoadError when no route of the modes has two stops.

#include "load/import_limits.hpp"
#include "load/metro_load.hpp"
#include "model/metro.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace tourmap::load {

struct OsmTransitStats {
  std::vector<std::string> modes;         // the modes read
  std::size_t routes = 0;                 // route relations of those modes
  std::size_t route_masters = 0;          // route masters over them
  std::size_t routes_without_stops = 0;   // fewer than two stops in the extract: not used
  std::size_t stops = 0;                  // stop and platform nodes (and ways) located
  std::size_t stations = 0;               // stations made of them
  std::size_t missing_stop_members = 0;   // stop/platform members not in the extract
  std::size_t skip_edges = 0;             // edges dropped beside a path of their lines (metro_osm.cpp)
};

// The modes read when none is asked for: the rail modes with routes in `present`, else bus.
std::vector<std::string> default_transit_modes(const std::vector<std::string>& present);

model::MetroNetwork load_metro_osm(const std::string& path, const std::vector<std::string>& modes = {},
                                   const ImportLimits& limits = {}, OsmTransitStats* stats = nullptr);

}  // namespace tourmap::load
