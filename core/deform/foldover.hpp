#pragma once
// Foldovers after a solve (paper 4.4.2 "Preventing foldovers"): inverted or non-convex quads,
// and road edges that cross after deformation but did not before; plus the optional relaxation
// step that smooths the vertices of folded quads until none is left (or a cap is hit).

#include "deform/system.hpp"

#include <chrono>
#include <cstddef>

namespace tourmap::deform {

// Quads whose deformed corners no longer turn counter-clockwise at every corner (CGAL exact
// orientation predicates).
std::size_t count_inverted_quads(const grid::Grid& grid, const std::vector<XY>& positions);

// Pairs of road edges without a shared node that intersect (CGAL box intersection + exact
// segment predicates).
std::size_t count_crossings(const std::vector<XY>& nodes, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges);

// Puts every T-junction vertex on the midpoint of its coarse quad's deformed side. The system keeps T-junctions near
// that midpoint only softly (support edges, 4.4.1); exactly there, the fine quads and the coarse
// one meet along one line, so the piecewise bilinear map has no crack or overlap and, with no
// quad folded, is one-to-one: roads cannot cross where they did not before (but for the straight
// chords drawn between their nodes).
void snap_tjunctions(const grid::Grid& grid, std::vector<XY>& positions);

// One smoothing step: each of `vertices` moves its free coordinates halfway towards its
// orthogonal neighbours' average (keeping its rest offset from it); then T-junctions are snapped.
void smooth_vertices(const Prepared& p, std::vector<XY>& points, const std::vector<std::uint32_t>& vertices);

// Two roads closer at rest than this (2 m, in map units) are taken as touching: their centre
// lines are less than a lane apart, so the roads themselves overlap (in OSM: a side road whose
// last node stops a metre short of the road it joins, a slip road along its carriageway), and a
// deformation that makes their lines cross has not added a crossing.
double touching_distance(const PlanarNetwork& net);

// Pairs of road edges without a shared node that cross at `nodes` but neither crossed nor touched
// at `rest` (CGAL box intersection + exact segment predicates).
std::size_t count_added_crossings(const PlanarNetwork& net, const std::vector<XY>& nodes);

// Distance between two segments (0 when they meet).
double segment_distance(XY a, XY b, XY c, XY d);

// Moves the free coordinates of folded quads' vertices halfway towards their orthogonal
// neighbours' average, repeatedly, snapping T-junctions after each step; returns the iterations run. Grid method only.
// Stops early, too, at `until`.
int relax_foldovers(const Prepared& p, std::vector<XY>& points, int max_iterations,
                    std::chrono::steady_clock::time_point until = std::chrono::steady_clock::time_point::max());

}  // namespace tourmap::deform
