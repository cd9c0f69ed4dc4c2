#pragma once
// A city's schematic drawn onto a laid-out page, as the client's Metro view draws it
// (web/src/metro/metro-layers.ts, bundles.ts, web/src/styles/map.css): white casings under the
// bundles, each line its own stroke in the edge's order, station symbols (a circle, a capsule
// across a bundle, interchanges outlined dark), the server's names with a white halo, then the
// title, legend and attribution.

#include "export/drawing.hpp"
#include "export/map_scene.hpp"
#include "export/page_layout.hpp"

namespace tourmap::map_export {

// The client's look (CSS px).
struct MapStyle {
  Color ink{0x1d / 255.0, 0x27 / 255.0, 0x33 / 255.0};        // --ink
  Color ink_soft{0x5b / 255.0, 0x66 / 255.0, 0x75 / 255.0};   // --ink-soft
  Color paper{1, 1, 1};
  double line_width_px = 3.5;
  double casing_margin_px = 3.5;     // a casing is its bundle's width plus this
  double station_outline_px = 2;     // in the line's colour
  double interchange_outline_px = 2.2;  // in ink
  double label_halo_px = 3;
  double label_halo_alpha = 0.9;
  double leader_width_px = 1;        // a name set off from its symbol (in ink)
  double swatch_radius_px = 3;
};

Drawing draw_map(const MapScene& scene, const PageLayout& page, const MapStyle& style = {},
                 const PageStyle& page_style = {});

// Shorthand: layout_page and draw_map.
Drawing draw_map(const MapScene& scene, double width_px, double height_px);

Color color_of(const Rgb& rgb);

}  // namespace tourmap::map_export
