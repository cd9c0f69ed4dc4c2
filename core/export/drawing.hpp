#pragma once
// A drawn page as a list of primitives in px (x right, y down), painted in order: what the
// SVG writer (svg_writer.hpp) and the cairo backends (cairo_render.hpp) both consume, so the
// three formats show the same thing.

#include "geo/projection.hpp"

#include <string>
#include <variant>
#include <vector>

namespace tourmap::map_export {

struct Color {
  double r = 0, g = 0, b = 0, a = 1;  // 0..1
};

// What a primitive shows (an SVG class, for readers and tests of the SVG).
enum class Role { background, title, casing, line, station, label, legend, attribution };

// Polylines stroked with round caps and joins (no fill).
struct Strokes {
  Role role = Role::line;
  std::vector<std::vector<geo::XY>> paths;
  Color color;
  double width = 1;
};

// A rectangle with rounded corners (radius r), rotated by `angle_deg` around its centre
// (clockwise on the page, y down): station symbols (a circle, or a capsule across a bundle),
// legend swatches, the background.
struct RoundedRect {
  Role role = Role::station;
  geo::XY center;
  double width = 0, height = 0, radius = 0, angle_deg = 0;
  Color fill;
  Color stroke;
  double stroke_width = 0;  // 0: no outline
};

// Text: one or more lines, each line_px below the one before, anchored at `at` (the first
// line's baseline). `fit_em`: per line, the width the layout measured it with, in ems (empty:
// the font's own width); a backend whose font differs stretches the line to it.
struct Text {
  Role role = Role::label;
  geo::XY at;
  std::vector<std::string> lines;
  std::vector<double> fit_em;
  double size_px = 12, line_px = 13;
  bool bold = true;
  char anchor = 's';  // 's' start, 'm' middle, 'e' end
  Color fill;
  Color halo;
  double halo_px = 0;  // 0: no halo
};

using Primitive = std::variant<Strokes, RoundedRect, Text>;

struct Drawing {
  double width = 0, height = 0;  // px
  std::string title;             // the document's title (SVG <title>, PDF metadata)
  std::string font_family;       // every text's family
  std::vector<Primitive> items;
};

}  // namespace tourmap::map_export
