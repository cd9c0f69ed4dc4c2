#pragma once
// Where everything goes on an exported page (px, x right, y down): the title at the top, the
// attribution at the foot, the legend beside or below the map (whichever leaves the schematic
// the larger scale), and the schematic fitted into the rest at the largest scale at which it,
// its symbols and its names fit. The names are the placement of the largest label scale at or
// below the page's scale (metro/station_labels.hpp: a placement holds at every larger scale),
// so no two overlap.

#include "export/map_scene.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace tourmap::map_export {

struct PageStyle {
  double margin_px = 28;
  double title_px = 30, title_gap_px = 14;
  double legend_font_px = 12, legend_row_px = 22, legend_gap_px = 18;  // gap: between legend and map
  double swatch_width_px = 26, swatch_height_px = 6, swatch_gap_px = 8, legend_column_gap_px = 22;
  double attribution_px = 10, attribution_line_px = 13, attribution_gap_px = 12;
  // The legend is left out when every place for it leaves the map less than this share of the
  // page's width or height.
  double min_map_share = 0.4;
};

struct Box {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
};

// A point to fit, in layout units, and how far what is drawn around it reaches in px
// (x right, y down from the point's place on the page), whatever the scale.
struct FitItem {
  geo::XY p;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// layout -> page: page x = origin.x + scale * x, page y = origin.y - scale * y.
struct Fit {
  double scale = 0;  // px per layout unit
  geo::XY origin;
};

// The largest scale at which every item fits in `box`, centred in it. Items that cannot fit at
// any scale (their px reach alone is wider than the box) are fitted by their points alone.
Fit fit_items(const std::vector<FitItem>& items, const Box& box);

geo::XY to_page(const Fit& fit, geo::XY p);

struct LegendEntry {
  std::size_t line = 0;   // index into MapScene::lines
  Box swatch;
  geo::XY text_at;        // the label's baseline start
};

struct TextLine {
  std::string text;
  geo::XY at;             // baseline start
};

struct PageLayout {
  double width = 0, height = 0;
  TextLine title;
  double title_px = 0;    // the title's size: the style's, smaller when the name is wider than the page
  Box map;                // the schematic's room
  Fit fit;
  int label_scale = -1;   // index into MapScene::label_scales; -1: no names fit this scale
  double symbol_px = 0;   // the stations' symbol radius at this scale
  std::vector<LegendEntry> legend;  // in legend order; empty when left out
  bool legend_beside = false;       // beside the map (else below it)
  std::vector<TextLine> attribution;
};

// The page of `width_px` x `height_px` for `scene`.
PageLayout layout_page(const MapScene& scene, double width_px, double height_px, const PageStyle& style = {});

// `text` broken at spaces into lines of at most `max_px` at `font_px` (a word longer than that
// stands alone on its line). Measured with the labels' font (metro/label_font.hpp).
std::vector<std::string> wrap_text(const std::string& text, double font_px, double max_px);

// The stations' symbol radius at `scale` (px per layout unit): the client's rule.
double symbol_radius_px(const MapScene& scene, double scale);

}  // namespace tourmap::map_export
