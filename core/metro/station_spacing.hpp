#pragma once
// Room around every station (issue 13: "a centre that breathes"): no station closer than
// `gap_share` of the mean edge to a station it is not joined to or to an edge it is not on.
//
// A linear program moves the stations and bend points of an octilinear layout while every
// segment keeps its direction, so bends, octilinearity and each station's circular order stay
// exactly as they are. With the directions fixed everything needed is linear in the points:
//   - a point is where it is now after a similarity (scale s in [0.8, 1.25] and a shift, free:
//     the whole map may grow) plus a move of at most `trust` mean edges per axis;
//   - a segment p->q in octilinear direction u: n.(q - p) = 0 (n normal to u), and its length
//     u.(q - p) >= a floor (its length now, up to `min_segment_share` of the mean edge);
//   - an edge's length (the sum over its segments) >= its target (eq. 5.4), or its length now
//     when that is shorter;
//   - the mean edge M = (sum of segment lengths) / edges;
//   - a station v clear of a segment pq: w.(v - e) >= tau M, with w the octilinear direction
//     that separates them best now and e the segment's end nearer to v along w (it stays the
//     nearer: the segment's direction is fixed). tau = gap_share * margin. Soft: a priced
//     slack, bounded so that the pair comes no closer than it is now;
//   - two segments of other edges kept apart: w.(a - b) >= min(now, delta M0), w the
//     octilinear direction that separates them best now, a and b their nearest ends along w,
//     so that no crossing appears.
// Objective: sum |move| (L1: few points move, the rest stay) + w_slack * sum of slacks.
// The pairs come in lazily (cutting planes): the program starts with the pairs near each other
// (within the rule plus `cut_radius`), and every pair a solution brings closer than its rule
// is added as a row and the program solved again from its last basis (dual simplex), until a
// solution needs none. So the trust region can be wide (a dense centre opens in one or two
// rounds: London 0.14 -> 0.51 of the mean edge in 2 rounds, 0.46 s, where a trust of 0.3 with
// every pair within reach up front took 8 rounds and 1.5 s) without a program of every pair
// it could bring together.
// The separating directions linearise around the current layout, so the program runs in rounds,
// each from the last one's result, and a round is kept only when the measured layout is better
// (a larger smallest gap) and no worse otherwise (no new crossing pair or order violation,
// still octilinear).
// Our own model because no packaged library does octilinear compaction with these rows (OGDF's
// compaction is orthogonal and not in Debian); CLP solves it (metro/lp_solve.hpp).

#include "metro/layout_graph.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace tourmap::metro {

struct SpacingParams {
  double gap_share = 0.5;          // the rule: smallest gap >= this * mean edge
  double margin = 1.06;            // asked with this margin (the solver's tolerance, the mean moves)
  double segment_share = 0.15;     // delta: clearance kept between segments of other edges
  double min_segment_share = 0.2;  // a segment's floor, in mean edges (or its length now if shorter)
  double trust = 1.5;              // a point's move per round, in mean edges
  double pair_radius = 1.25;       // pairs in the program from the start: station-segment ones nearer than this * the gap
  double cut_radius = 0.3;         // + 2 cut_radius mean edges, segment pairs nearer than delta + 2 cut_radius; the rest
  int max_cuts = 12;               // ...as cuts, when a solution brings them too close (at most this many passes)
  double w_station = 1.0, w_bend_point = 0.5;  // per unit of a point's move
  double w_slack = 300.0;          // per unit of a clearance short of the rule (at 60 London uniform stalled at 0.37)
  int max_rounds = 12;
  double time_limit_ms = 400.0;    // this thread's CPU time for starting rounds (one in progress finishes)
};

struct SpacingReport {
  std::string status;              // "met", "improved", "no_gain", "time_limit", "skipped", "solver"
  double gap_before = 0, gap_after = 0;  // smallest gap / mean edge
  int rounds = 0, accepted = 0;
  std::size_t columns = 0, rows = 0;     // of the last program
  std::size_t cuts = 0;                  // pair rows added to the programs as cuts
  double time_ms = 0;                    // wall time
};

// `g`: the graph (targets in g.min_length); `layout` octilinear, changed in place when a round
// is kept (positions and paths; method and status stay).
SpacingReport space_stations(const LayoutGraph& g, Layout& layout, const SpacingParams& params = {});

// Room for a station's name (issue 14): a box in px from the station's point (x right, y
// down) at the zoom where the mean edge is `scale_px` on screen, so in layout units it grows
// with the mean edge M: the program keeps it clear of other edges' lines (by half their
// bundle and `clearance_px`) and of other stations' symbols (`symbol_px` and the clearance).
struct LabelRoom {
  std::uint32_t station = 0;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
struct LabelRoomParams {
  double scale_px = 75;          // the mean edge on screen the boxes are sized for
  double line_spacing_px = 4;    // a bundle of n lines is n of these wide
  double clearance_px = 1;
  double label_gap_px = 2;       // between two names
  double symbol_px = 8;          // a symbol's radius
  double radius = 1.0;           // obstacles within this many mean edges of a box get a row
  double move_radius = 5.0;      // points within this many mean edges of a room's station move; the rest stay
  double w_room = 100.0;         // per unit of a box's clearance short of its need
  // The placed names near a room kept clear of the lines and symbols they are clear of now
  // (hard rows; off: a try for one name may cost others theirs, for the caller to weigh).
  bool keep_placed = true;
};

// One round of the spacing program (the same columns, direction, floor and gap rows, with
// cuts) that also asks each box in `rooms` for its clearance, as soft rows priced by w_room.
// The caller decides whether to keep the result (the names it gains, the gap it keeps): none
// when the program has no solution or the layout is not octilinear.
// `placed`: the names placed at that zoom, kept clear of the rooms' boxes (by label_gap_px).
std::optional<Layout> make_room_for_labels(const LayoutGraph& g, const Layout& layout, const std::vector<LabelRoom>& rooms,
                                           const std::vector<LabelRoom>& placed, const LabelRoomParams& room,
                                           const SpacingParams& params = {});

}  // namespace tourmap::metro
