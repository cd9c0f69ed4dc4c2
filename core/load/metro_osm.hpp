#pragma once
// A transit line graph from the route relations of an OSM extract (issue 16, part 1), through
// libosmium in two passes over the file (decompressed and bounded once, osm_input.hpp):
//  1. relations: routes (type=route, route=<mode>), their route masters (type=route_master: one
//     line for the routes of both directions), stop areas (public_transport=stop_area); of each
//     route its stop and platform members, its other node members, and its track: the way
//     members of other roles ("", forward, backward, ...), in member order;
//  2. nodes and ways: the positions and names of the routes' stops and platforms (a platform way
//     at its nodes' mean), and the node positions of the track ways.
// Modes: subway, light_rail, tram, train, bus, ferry (also monorail, funicular, trolleybus);
// none asked: the rail modes with a route of two stops in the extract (subway, light_rail, tram,
// train, monorail, funicular), else bus (Monaco's extract holds a train route whose stations all
// lie outside it: a bus map).
//
// Lines: one per route master (else per mode and ref, else per route), id "r<osm id>", label
// ref (else name), colour colour=#rrggbb of the master or a route. Stations: the stops of one
// stop area are one station; other stops of one name (case-insensitive, over two characters:
// "1" names a platform's track) within 400 m of each other are one station; a stop without
// such a name joins the nearest station within 150 m, else is a station of its own named after
// the nearest named way of the routes' track within 60 m (the street of a bus stop). Station
// id "s" and its first stop's "n<node id>" or "w<way id>", at the mean of its stops. A route's
// stations in the order of its stop positions (role stop*; of its platforms, role platform*,
// where fewer than two stop positions are in the extract; of its other node members, as older
// routes list their stops with role "", where neither has two), the same station twice in a
// row once, give its line's edges; lines on the same two stations share one edge; an edge
// whose lines also run through the stations along it (one direction listing fewer stops, an
// express) is dropped. Older routes serving both directions in one relation mark their stops
// forward_stop and backward_stop (platforms alike; the ends where they turn plain stop) and list
// the way back's stops after the way out's: one sequence, the way back's along the track reversed.
//
// Edge geometry follows the track. A route's ways are chained in member order, each turned to
// continue the chain (the first one to run into the ways listed after it), a closed way (a
// roundabout) entered at any node and followed in its direction to where a next way leaves it.
// Breaks are repaired where the member list allows one reading (metro_osm.cpp, TrackAssembler):
// a way listed up to 3 places out of order; the first way turned the wrong way; a way leaving
// from a node the chain passed up to 300 m back (a roundabout split into ways and listed whole,
// a junction inside a way: the excursion is dropped) or up to 5 km back (a branch run up and
// back but listed once: the chain runs back down it); the chain's end inside a way; a gap of up
// to 100 m (a junction or roundabout way left out) drawn straight. A way meeting nothing, listed
// before ways already taken, is left out; any other break cuts the track in pieces (a gap). Each
// station is placed on the track at the nearest point within 150 m (bus stops stand beside the
// road, platforms beside the track), searched forward from the previous station's place in the
// first stretch of track that comes that close (a later pass along the same street is another
// stop's); a track ending where it starts (a loop) may be gone round twice; a route whose ways
// are listed against the order of its stops has its track reversed. An edge gets the track
// between its two stations' places with the stations' positions at its ends, simplified
// (Douglas-Peucker, 3 m), oriented from the edge's `from` to its `to`; the first route giving an
// edge a track wins (MetroBuilder::replace_straight_geometry). An edge stays straight where no
// route has track between its stations: no track ways in the extract, a gap, a station off the
// track, the route turning back between them, or a track running far around (more than 4 times
// the straight distance plus 2 km: a wrong placement). Lines running on the same track between
// different stations are drawn side by side: the topo step collapsing them into shared
// segments is not done.
//
// Nothing is dropped silently: routes not used (fewer than two stops in the extract), a route's
// track ways missing from the extract or left out, gaps repaired and left, and edges left
// straight with the reason are counted in the stats and reported per relation
// (OsmTransitStats::problems, at most kMaxOsmRouteProblems). Bounded by the OSM limits
// (max_osm_*; max_osm_track_points for the track), the metro limits of the network built
// (max_metro_*, metro_builder.hpp) and max_name_bytes. Polls util::check_stop(). Throws
// LoadError when no route of the modes has two stops.

#include "load/import_limits.hpp"
#include "load/metro_load.hpp"
#include "model/metro.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tourmap::load {

// One problem with one route relation, e.g. "relation 123 (bus 11): 2 gaps in the track, between
// ways 456 and 789, between ways 790 and 801", "relation 124 (train RJ): fewer than two stops in
// the extract, not used", "relation 125 (bus 2): 1 of 14 edges straight: Markt - Post (a gap in
// the track)".
struct OsmRouteProblem {
  std::int64_t relation = 0;  // the OSM id of the route relation
  std::string message;        // names the relation, its mode and ref (or name)
};

// At most this many problems are listed (OsmTransitStats::problems); the rest are counted.
inline constexpr std::size_t kMaxOsmRouteProblems = 100;

struct OsmTransitStats {
  std::vector<std::string> modes;         // the modes read
  std::size_t routes = 0;                 // route relations of those modes
  std::size_t route_masters = 0;          // route masters over them
  std::size_t routes_without_stops = 0;   // fewer than two stops in the extract: not used
  std::size_t stops = 0;                  // stop and platform nodes (and ways) located
  std::size_t stations = 0;               // stations made of them
  std::size_t missing_stop_members = 0;   // stop/platform members not in the extract
  std::size_t skip_edges = 0;             // edges dropped beside a path of their lines (metro_osm.cpp)
  // Track geometry (edges counted in the network returned, after the skip edges are dropped).
  std::size_t routes_with_track = 0;      // used routes with some track in the extract
  std::size_t track_edges = 0;            // edges with a geometry cut from a route's track
  std::size_t straight_edges = 0;         // edges left straight: no route had track between their stations
  std::size_t gaps_repaired = 0;          // breaks in a route's way order repaired (see above)
  std::size_t gaps = 0;                   // breaks left: the route's track is in pieces there
  std::size_t missing_track_members = 0;  // track ways of the used routes not in the extract
  std::size_t skipped_track_members = 0;  // track ways meeting neither the ways before nor after them: left out
  std::size_t track_points = 0;           // the track's work, as max_osm_track_points counts it
  std::vector<OsmRouteProblem> problems;  // per relation, in file order, at most kMaxOsmRouteProblems
  std::size_t problems_left_off = 0;      // problems beyond those listed
};

// The modes read when none is asked for: the rail modes with routes in `present`, else bus.
std::vector<std::string> default_transit_modes(const std::vector<std::string>& present);

model::MetroNetwork load_metro_osm(const std::string& path, const std::vector<std::string>& modes = {},
                                   const ImportLimits& limits = {}, OsmTransitStats* stats = nullptr);

}  // namespace tourmap::load
