#pragma once
// GET /api/v1/cities/{id}/map.svg | map.pdf | map.png (issue 14): a city's octilinear
// schematic as a printable map, drawn on the server (core/export) from the same cached layout
// answer the Metro view draws, at a requested size.
//
// The page is laid out in CSS px (1/96 in): station names are 12 px like the client's, i.e.
// 9 pt on paper. Sizes:
//   paper=a4|a3 [orientation=landscape|portrait]  the paper's size: SVG in mm, PDF in points,
//                                                  PNG at `dpi` (A3 at 300 dpi: 4961 x 3508 px)
//   width, height                                  SVG and PNG in px, PDF in points
//   dpi (PNG only, 72..600, default 96)            px per inch: the page is the image's size
//                                                  times 96 / dpi in CSS px
// Neither paper nor width and height: A3 landscape. Bounds (kMap* below): each side 200 to
// 10,000 px (PDF 14,400 pt, PDF's own limit), the page at least 200 CSS px a side, a PNG at
// most 36 million px (A3 at 400 dpi fits; A2 at 300 dpi too). The layout's own parameters
// (lengths, solver, ...) are the layout route's and select the same cached layout.

#include "http.hpp"
#include "metro_service.hpp"

#include "export/map_scene.hpp"

#include <string>

namespace tourmap::api {

enum class MapFormat { svg, pdf, png };

inline constexpr double kMapMinSide = 200;        // px or pt; also the page's least side in CSS px
inline constexpr double kMapMaxSide = 10000;      // px (SVG, PNG)
inline constexpr double kMapMaxPdfSide = 14400;   // pt: 200 in, the PDF format's page limit
inline constexpr double kMapMaxPngPixels = 36e6;  // A3 at 300 dpi is 17.4 million
inline constexpr double kMapMinDpi = 72, kMapMaxDpi = 600, kMapDefaultDpi = 96;

struct MapPage {
  MapFormat format = MapFormat::svg;
  double page_width = 0, page_height = 0;  // CSS px: what the map is laid out in
  double out_width = 0, out_height = 0;    // SVG, PNG: px; PDF: pt
  std::string svg_width, svg_height;       // the SVG root's size ("420mm" on paper)
  std::string paper;                       // "a4", "a3", or empty (a custom size)
};

// From the query; ApiError 400 naming the field (413 for a PNG of too many pixels).
MapPage parse_map_page(const Request& req, MapFormat format);

// The file's bytes for a scene on a page.
std::string render_map(const map_export::MapScene& scene, const MapPage& page);

const char* map_content_type(MapFormat format);
const char* map_extension(MapFormat format);

// The route's handler.
Response serve_map(MetroService& metro, const Request& req, MapFormat format);

}  // namespace tourmap::api
