#pragma once
// The sea of an OSM extract from its coastline (natural=coastline ways): pure geometry on
// lon/lat polylines, no libosmium. OSM draws the coastline with the land on its left and the
// water on its right. Within an extract the coastline is mostly open: it leaves the extract's
// bounds, so libosmium's area assembler (closed rings only) cannot build the sea, and no
// library in the Debian set closes it along a box (osmcoastline does it for the whole planet,
// but it is a program and not packaged as a library). So, here:
//
//  1. Ways are joined end to end into chains by node id (the first node of one is the last
//     node of the previous one; a way drawn the wrong way round does not join).
//  2. Chains are clipped to the box. A chain end inside the box counts as reaching the box when
//     it is within `snap_fraction` of the box's larger side from a side (extracts cut along a
//     polygon end their ways near the polygon, not on the box: Monaco's coastline ends 560 m
//     short of its node box) and is then extended straight to that side. A chain with an end
//     farther inside is broken (a gap in the data).
//  3. Each piece's end is joined to the next piece's start clockwise along the box (adding the
//     corners passed), keeping the water on the right, until the ring closes: each ring is sea.
//     Along the box the pieces' ends and starts must alternate (end, start, end, ...).
//  4. A closed chain inside the box with the land inside (counter-clockwise) is an island: a
//     hole in the smallest sea ring around it. One with the water inside (clockwise) is sea.
//     Without any open chain, the box is sea around the islands that lie in no such ring.
//
// Broken chains, or ends and starts that do not alternate along the box (a coastline drawn
// the wrong way), mean the sea cannot be told from the land near them: then no sea is made
// from the open chains at all (rather than a wrong polygon), and the chains are counted.

#include "geo/lonlat.hpp"
#include "geo/polygon.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tourmap::load {

struct CoastlineWay {
  std::vector<std::int64_t> node_ids;  // OSM node ids, one per point
  std::vector<geo::LonLat> points;     // the way's located nodes, in way order
};

struct CoastlineSea {
  // Outer ring counter-clockwise, holes clockwise; no repeated closing point.
  std::vector<geo::Polygon> seas;
  std::size_t chains = 0;         // chains after joining the ways
  std::size_t islands = 0;        // closed chains with the land inside, within the box
  std::size_t broken_chains = 0;  // open chains that could not be used (see above)
};

CoastlineSea sea_from_coastlines(const std::vector<CoastlineWay>& ways, const geo::BBox& box,
                                 double snap_fraction = 0.05);

// Twice the signed area of a ring (shoelace over lon/lat): > 0 counter-clockwise.
double signed_area2(const std::vector<geo::LonLat>& ring);
// True when `p` is inside `ring` (even-odd crossings; points on the boundary may go either way).
bool ring_contains(const std::vector<geo::LonLat>& ring, geo::LonLat p);

}  // namespace tourmap::load
