#pragma once
// Station names on an octilinear metro map (issue 14), one placement for the client and the
// export. A label is a box of the name's width (metro/label_font.hpp) in one of sixteen places
// around its station's symbol: east, north-east, ..., south-east, and beside a line leaving
// east, west, north or south (slid off it to either side), on one line of text or, for a name
// of several words, on two (split after the space or hyphen that makes the halves most even).
// Labels keep clear of each other, of every line (a bundle of n lines is n * line spacing wide), and of every station's
// symbol. Interchanges and termini are named first, then by priority; a label takes the free
// place that reads best (east first, then west, the diagonals, north and south) and prefers
// the side its neighbour on the line took. Where none of those places is free (a dense centre),
// the name may sit anywhere around the symbol (a box touching the ring of its sixteen places at
// one of 48 angles), and last of all a little further out, joined to the symbol by a thin
// leader that keeps clear of lines, symbols and other names (a callout, as map makers use in
// crowded areas). A second pass names a station left out by moving up to three labels in its
// way to other free places.
//
// Label sizes are pixels and the map zooms, so a placement is made per scale (px per layout
// unit). A client shows a placement from its zoom until the next one's: there the boxes keep
// their size while the stations spread, so two names pointing towards each other could meet
// at a zoom in between. Every pair of names is checked over that whole range (exactly: on each
// axis two boxes overlap on a half-line in 1 / zoom). Lines and symbols only move away from a
// name as the zoom grows: they are checked at the placement's zoom, with the symbols as big
// as they get before the next placement takes over. A client shows the placement of the
// largest scale at or below its zoom (cartographic label placement: Christensen, Marks,
// Shieber, ACM TOG 1995, greedy with local repair; the conflict-graph formulation in
// DESIGN.md's references).

#include "metro/label_font.hpp"
#include "metro/layout_graph.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tourmap::metro {

struct LabelStyle {
  double font_px = 12;           // the name's size
  // From the zoom names go round the ring on, a name that fits nowhere in font_px is tried in
  // this size (height and line spacing scaled alike); 0: never.
  double small_font_px = 10;
  double height_px = 14;         // its box's height (one line; each more adds line_px)
  double line_px = 13;           // from one line of a name's text to the next
  double gap_px = 3;             // between a symbol and its label
  double line_spacing_px = 4;    // centre to centre of parallel lines (the client's)
  double line_width_px = 3.5;
  double clearance_px = 1;       // kept free around lines and symbols
  double label_gap_px = 2;       // between two names (touching, "Cyprus" and "Gallions Reach" read as one)
  double leader_step_px = 8;     // a name on a leader sits 1 to 7 steps beyond its nearer places
  // Names go round the ring and onto leaders only from this zoom on (symbols 12 px across):
  // in an overview, a name that does not fit beside its symbol is better left out.
  double ring_min_mean_edge_px = 75;
  // From that zoom on, a name still left out and up to this many names around it are placed
  // again together, exactly within a search limit (metro/label_choice.hpp); 0: never.
  std::size_t exact_group = 24;
  // A station symbol's radius grows with the zoom: this share of the mean edge on screen, within
  // [min, max] px. A symbol on a bundle of n lines reaches (n - 1) / 2 line spacings further.
  // 12 px across at 75 px, the first zoom names are placed for with the ring (with a tenth,
  // symbols were 12 px from 60 px on, where the 50 px placement without the ring is shown).
  double symbol_share = 0.08, symbol_min_px = 3, symbol_max_px = 8;
  double symbol_px(double mean_edge_px) const;
};

// One placed label, in pixels relative to its station's point (x right, y down).
struct PlacedLabel {
  std::uint32_t node;
  int position;                 // 0..7: the side, counter-clockwise from east (2 north, 4 west)
  int slide;                    // -1, 0, 1: slid off a line leaving that side (0: centred on the side)
  double x0, y0, x1, y1;        // the box
  double text_x, text_y;        // the text's anchor point (on the first line's baseline)
  char anchor;                  // 's' start, 'm' middle, 'e' end of the text at text_x
  std::size_t split = 0;        // two lines: the byte where the second begins (0: one line)
  bool leader = false;          // joined to the symbol by a leader from (lx0, ly0) to (lx1, ly1)
  double lx0 = 0, ly0 = 0, lx1 = 0, ly1 = 0;
  int candidate = -1;           // which of the placer's places it is (for a later placement to keep)
  double font_px = 0;           // its type size (the style's, or its small_font_px)
};

struct LabelScale {
  double px_per_unit = 0;       // the scale: pixels per layout unit
  double mean_edge_px = 0;      // the mean edge at that scale
  double symbol_px = 0;         // the symbols' radius the placement kept clear of
  std::vector<PlacedLabel> labels;
  std::size_t unlabelled = 0;   // named stations without a label at this scale
  std::size_t no_room = 0;      // of those, how many have no place clear of lines and symbols
  std::size_t leaders = 0;      // labels on a leader
  std::size_t small = 0;        // labels in the smaller type
  // From the zoom where names go round the ring on: for each station left unnamed, the place
  // its name would take given room (the one the fewest lines and symbols stand in, none of
  // them its own), for the layout to make room (metro/station_spacing.hpp, LabelRoom); once in
  // font_px and, where the style has a smaller type, once more in that (see font_px).
  std::vector<PlacedLabel> wanted;
  // And for each of them its six places (of the sixteen, in either type) that need the least
  // room: the lines and symbols in them moved the least distance out, best first.
  std::vector<PlacedLabel> alternatives;
};

struct StationLabelInput {
  std::vector<std::string> names;     // per node; empty: not a station (no label)
  std::vector<double> priority;       // per node: higher is named first
  std::vector<std::size_t> lines;     // per edge: how many lines run on it (the bundle's width)
};

// Placements for each scale in `mean_edges_px` (the mean edge on screen), smallest first.
// `before`: an earlier placement on the same scales (of a layout since moved a little, as room
// for names is made): each station first tries the place it had there, or for one left out
// the place it wanted, where that is still free; the rest are placed as usual. Without it a
// round that made room for a few names re-placed them all, and as many were lost as gained.
std::vector<LabelScale> place_station_labels(const LayoutGraph& g, const Layout& layout, const StationLabelInput& in,
                                             const std::vector<double>& mean_edges_px, const LabelStyle& style = {},
                                             const std::vector<LabelScale>* before = nullptr);

// The width of a name in the labels' font at `style.font_px`.
double label_width_px(const std::string& name, const LabelStyle& style);

}  // namespace tourmap::metro
