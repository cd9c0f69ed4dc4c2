#pragma once
// What a printed metro map shows (issue 14, export): a city's octilinear schematic as the
// client draws it, in plain structs. The api/ fills it from the layout answer (the one the
// client draws from), so an export and the Metro view show the same line order, names,
// symbols, legend and attribution. Coordinates are the layout frame's units (metres, x east,
// y north); every size on the page is in px.

#include "geo/projection.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tourmap::map_export {

struct Rgb {
  std::uint8_t r = 0x8a, g = 0x90, b = 0x99;  // the client's colour for a line without one
};

struct SceneLine {
  std::string id, label;
  Rgb color;
};

// An end of an edge: a station (it has a symbol and may have a name) or a junction.
struct SceneNode {
  geo::XY pos;
  bool station = false;
  std::string name;
  std::vector<std::uint32_t> lines;  // lines serving it (indices into MapScene::lines)
};

struct SceneEdge {
  std::uint32_t from = 0, to = 0;    // nodes
  std::vector<geo::XY> path;         // from -> to
  std::vector<std::uint32_t> order;  // its lines, left to right travelling from -> to
};

// A station name placed by the server (metro/station_labels.hpp): px from the station's point,
// x right, y down.
struct SceneLabel {
  std::uint32_t node = 0;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the box
  double text_x = 0, text_y = 0;          // the anchor on the first line's baseline
  char anchor = 's';                      // 's' start, 'm' middle, 'e' end
  std::size_t split = 0;                  // byte where a second line begins (0: one line)
  double font_px = 0;                     // its type size (0: the style's)
  bool leader = false;                    // set off on a leader from (lx0, ly0) to (lx1, ly1)
  double lx0 = 0, ly0 = 0, lx1 = 0, ly1 = 0;
};

// The placement made for one scale: valid at that scale and every larger one.
struct SceneLabelScale {
  double px_per_unit = 0;
  std::vector<SceneLabel> labels;
};

// The labels' style as the layout answer gives it (metro::LabelStyle's values by default).
struct SceneLabelStyle {
  double font_px = 12, line_px = 13;
  double symbol_share = 0.08, symbol_min_px = 3, symbol_max_px = 8;
  double line_spacing_px = 4;
};

struct MapScene {
  std::string title;                           // the city's name
  std::vector<SceneLine> lines;
  std::vector<SceneNode> nodes;
  std::vector<SceneEdge> edges;
  std::vector<SceneLabelScale> label_scales;   // smallest first
  SceneLabelStyle label_style;
  double mean_edge = 0;                        // mean edge length in layout units (symbol size)
  std::vector<std::string> attribution;        // one line each, as the data's publishers ask
};

}  // namespace tourmap::map_export
