#pragma once
// The streets in the schematic's space (beyond the paper: the future work of chapter 4; issue
// 16): a city's road map warped into its octilinear metro layout, so that the streets around
// each station are drawn where the schematic draws the station. Chapter 4's machinery, as in
// the mental-map application (deform/applications.hpp):
//   1. A Helmert transformation (5.4.3, metro/warp.hpp), fitted from the stations' layout
//      positions to their geographic ones, brings the layout into the road map's plane, so the
//      deformation only has to do the residual.
//   2. The roads are cropped to the stations' bounding box plus a margin; each station snaps to
//      its nearest road node, which becomes a guide vertex pulled to the station's aligned
//      layout position (eq. 4.6/4.7; one guide per node, stations far from any road get none).
//   3. The road map is deformed on the adaptive grid (4.4.1, refined down to the guides, eq.
//      4.5 with the guide term), fold-overs relaxed and added crossings smoothed (4.4.2,
//      deform/deformer.hpp). A schematic moves stations by up to kilometres relative to their
//      neighbours (Liechtenstein's buses: 1 km rms after the Helmert fit, for a mean edge of
//      770 m); one linear solve, which keeps every road edge's direction, folds the grid there
//      and relaxing the folds gives most of the move back. So the deformation runs in steps,
//      each on a new grid over the roads as the last step left them, asking for an equal share
//      of what is left of the guides' moves.
//   4. Every road polyline, with points inside its edges, is carried through the deformed
//      grids (deform::map_points) and back into the layout's frame by the inverse Helmert
//      transformation: the drawing is the roads' image under the deformation, which is
//      one-to-one where no quad folded.
// What is achieved is reported, not guaranteed: where the layout moves neighbouring stations
// far apart or across each other, a guide stays short of its target rather than fold the map.
// No I/O; polls util::check_stop() (the solver does too).

#include "deform/problem.hpp"
#include "deform/solver.hpp"
#include "geo/lonlat.hpp"
#include "geo/projection.hpp"
#include "model/road.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace tourmap::metro {

struct SchematicStation {
  geo::LonLat geo;  // where the station is
  geo::XY layout;   // where the schematic draws it (the layout's planar frame, any unit)
};

// The road classes drawn under a schematic, from the most to the least important. Service
// roads, paths, tracks and footways are left out: under a metro map they are clutter, and a
// station should snap to the street it stands on, not to a platform's footpath.
enum class RoadRank : std::uint8_t { major, medium, minor };
inline constexpr int kRoadRanks = 3;

// The rank of an OSM highway=* value (as the web client groups them): major = motorway, trunk,
// primary (and links); medium = secondary, tertiary (and links); minor = residential,
// unclassified, living_street, road; nullopt for anything else.
std::optional<RoadRank> road_rank(std::string_view highway);
const char* road_rank_name(RoadRank rank);

struct SchematicRoadsParams {
  // Crop: the stations' bounding box grown on every side by the larger of these.
  double margin_share = 0.15;   // of the box's longer side
  double margin_min_m = 500.0;
  // A station farther than this from every kept road node gets no guide.
  double max_snap_m = 300.0;
  // At most this many road edges are deformed: beyond it the least important ranks go, whole.
  // (Liechtenstein's 14k kept edges take about 0.8 s; the cost grows with the edges, and the
  // grid's unknowns are bounded below.)
  std::size_t max_edges = 300000;
  // Adaptive grid (4.4.1): `grid_base` cells along the longer side; guides refine down to a
  // finest cell of at most `guide_cell_share` of the smallest distance between two guides
  // (so no two guides share a quad), but no deeper than `max_depth`; quads holding more than
  // `split_vertices` road nodes split as well.
  int grid_base = 10;
  int min_depth = 3;
  int max_depth = 5;  // deeper grids concentrate a guide's pull on a few small quads, which fold
  double grid_margin = 0.3;  // the frame around roads and targets, as a share of their extent: room to move
  double guide_cell_share = 0.5;
  int split_vertices = 16;
  // Unknowns: a grid with more than `max_direct_unknowns` is solved by CG instead of Cholesky;
  // one with more than `max_unknowns` is coarsened (less depth, more vertices per quad).
  std::size_t max_direct_unknowns = 60000;
  std::size_t max_unknowns = 250000;
  // The deformation runs in this many steps, each on a new grid over the roads as the last
  // one left them, asking for an equal share of what is left of the guides' moves.
  int steps = 6;
  // Roads are drawn through points at most this far apart (metres), each carried through the
  // grids: the image of a road under the deformation, not the chord between its nodes.
  double sample_spacing_m = 25.0;
  // After each step, also smooth away the crossings of chords between deformed nodes
  // (deform/untangle.hpp): crossings left by one step would be part of the next one's rest.
  bool untangle_chords = true;
  // Guides weigh 10x the mental-map default: stations should sit on their streets.
  deform::Weights weights{1.0, 0.3, 0.5, 1000.0};
  deform::Boundary boundary = deform::Boundary::sliding;
  int cg_max_iterations = 20000;
  double cg_time_limit_ms = 10000.0;
  double correction_budget_ms = 500.0;  // per step: fold-over relaxation and untangling together
  int relax_iterations = 100;
};

struct SchematicRoad {
  std::uint32_t way = 0;  // index into the input RoadNetwork::ways (a way may give several pieces)
  RoadRank rank = RoadRank::minor;
  std::vector<geo::XY> points;  // in the layout's frame
};

struct SchematicRoadsStats {
  std::size_t stations = 0;
  std::size_t guides = 0;
  std::size_t far_stations = 0;     // no kept road node within max_snap_m
  std::size_t shared_nodes = 0;     // a nearer station took the same road node
  std::size_t road_edges = 0;       // edges deformed (after the crop)
  std::size_t cropped_out_edges = 0;  // kept ranks' edges outside the crop box
  std::size_t dropped_edges = 0;    // inside the box but of a rank dropped for max_edges
  int ranks_kept = kRoadRanks;      // major..(ranks_kept - 1)
  int steps = 0;
  std::size_t edge_points = 0;      // points inside road edges carried through the grids
  int grid_depth = 0;
  int split_vertices = 0;
  std::size_t quads = 0;
  std::size_t unknowns = 0;
  bool cholesky = true;
  int iterations = 0;
  bool converged = false;
  // Helmert transformation layout -> road map (in layout units per metre and degrees), and the
  // stations' residual after it (layout units): what the deformation had to do.
  double helmert_scale = 1.0;  // map metres per layout unit
  double helmert_rotation_deg = 0.0;
  double helmert_rms = 0.0;
  double helmert_max = 0.0;
  // Guided road nodes after the deformation vs their targets, layout units.
  double max_guide_error = 0.0;
  double mean_guide_error = 0.0;
  // Every station's geographic position carried through the deformed grid vs its layout
  // position (including stations without a guide), layout units.
  double max_station_error = 0.0;
  double mean_station_error = 0.0;
  std::size_t foldovers = 0;        // quads still inverted after relaxation
  int relax_iterations = 0;         // the last step's
  std::size_t untangle_left = 0;    // the last step's added crossings left when its budget ran out
  // Pairs of road pieces (between nodes and edge points) that cross in the drawing but neither
  // crossed nor touched in the geography.
  std::size_t crossings_added = 0;
  double crop_ms = 0, grid_ms = 0, assembly_ms = 0, factor_ms = 0, solve_ms = 0, place_ms = 0, crossings_ms = 0, total_ms = 0;
};

struct SchematicRoadsResult {
  std::vector<SchematicRoad> roads;
  SchematicRoadsStats stats;
};

// Throws std::invalid_argument with fewer than two stations at distinct places.
SchematicRoadsResult schematic_roads(const model::RoadNetwork& roads, const std::vector<SchematicStation>& stations,
                                     const SchematicRoadsParams& params = {});

}  // namespace tourmap::metro
