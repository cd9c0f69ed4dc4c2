#include "map_export.hpp"

#include "map_scene_json.hpp"
#include "params.hpp"

#include "export/cairo_render.hpp"
#include "export/map_drawing.hpp"
#include "export/svg_writer.hpp"
#include "util/elapsed.hpp"

#include <cmath>
#include <cstdio>
#include <tuple>

namespace tourmap::api {
namespace {

using util::Clock;
using util::ms_since;

constexpr double kCssPxPerInch = 96, kPtPerInch = 72, kMmPerInch = 25.4;

struct Paper {
  const char* name;
  double long_mm, short_mm;
};
constexpr Paper kPapers[] = {{"a4", 297, 210}, {"a3", 420, 297}};

std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// The page in CSS px for an output side: px at dpi (PNG), pt (PDF), px (SVG).
double page_side(MapFormat format, double out, double dpi) {
  if (format == MapFormat::pdf) return out * kCssPxPerInch / kPtPerInch;
  if (format == MapFormat::png) return out * kCssPxPerInch / dpi;
  return out;
}

void set_paper(MapPage& page, const Paper& paper, bool portrait, double dpi) {
  const double w_mm = portrait ? paper.short_mm : paper.long_mm, h_mm = portrait ? paper.long_mm : paper.short_mm;
  page.paper = paper.name;
  page.page_width = w_mm / kMmPerInch * kCssPxPerInch;
  page.page_height = h_mm / kMmPerInch * kCssPxPerInch;
  switch (page.format) {
    case MapFormat::svg:
      page.out_width = page.page_width;
      page.out_height = page.page_height;
      page.svg_width = format_number(w_mm) + "mm";
      page.svg_height = format_number(h_mm) + "mm";
      break;
    case MapFormat::pdf:
      page.out_width = w_mm / kMmPerInch * kPtPerInch;
      page.out_height = h_mm / kMmPerInch * kPtPerInch;
      break;
    case MapFormat::png:
      page.out_width = std::round(w_mm / kMmPerInch * dpi);
      page.out_height = std::round(h_mm / kMmPerInch * dpi);
      break;
  }
}

void check_png_pixels(const MapPage& page, const std::string& field) {
  if (page.format != MapFormat::png) return;
  const double pixels = page.out_width * page.out_height;
  if (pixels > kMapMaxPngPixels)
    throw too_large(field, format_number(page.out_width) + " x " + format_number(page.out_height) + " px is " +
                               format_number(pixels / 1e6) + " million pixels; at most " +
                               format_number(kMapMaxPngPixels / 1e6) + " million");
}

}  // namespace

const char* map_content_type(MapFormat format) {
  switch (format) {
    case MapFormat::svg: return "image/svg+xml";
    case MapFormat::pdf: return "application/pdf";
    case MapFormat::png: return "image/png";
  }
  return "application/octet-stream";
}

const char* map_extension(MapFormat format) {
  switch (format) {
    case MapFormat::svg: return "svg";
    case MapFormat::pdf: return "pdf";
    case MapFormat::png: return "png";
  }
  return "bin";
}

MapPage parse_map_page(const Request& req, MapFormat format) {
  MapPage page;
  page.format = format;
  const auto* paper = req.query_param("paper");
  const auto* width = req.query_param("width");
  const auto* height = req.query_param("height");
  if (req.query_param("dpi") && format != MapFormat::png)
    throw bad("dpi", std::string("only map.png has a resolution; map.") + map_extension(format) +
                         (format == MapFormat::pdf ? " is sized in points" : " in px"));
  const double dpi = query_number(req, "dpi", kMapMinDpi, kMapMaxDpi, kMapDefaultDpi);
  if (paper && (width || height)) throw bad(width ? "width" : "height", "give either paper or width and height");
  if (!paper && (width || height)) {
    if (!width) throw bad("width", "required with height");
    if (!height) throw bad("height", "required with width");
    if (req.query_param("orientation")) throw bad("orientation", "only with paper");
    const double max = format == MapFormat::pdf ? kMapMaxPdfSide : kMapMaxSide;
    page.out_width = query_number(req, "width", kMapMinSide, max, 0);
    page.out_height = query_number(req, "height", kMapMinSide, max, 0);
    if (format == MapFormat::png) {
      page.out_width = std::round(page.out_width);
      page.out_height = std::round(page.out_height);
    }
    page.page_width = page_side(format, page.out_width, dpi);
    page.page_height = page_side(format, page.out_height, dpi);
    for (const auto& [field, side, out] : {std::tuple{"width", page.page_width, page.out_width},
                                           std::tuple{"height", page.page_height, page.out_height}})
      if (side < kMapMinSide)
        throw bad(field, format_number(out) + " px at " + format_number(dpi) + " dpi is a page of " +
                             format_number(std::round(side)) + " px (1/96 in); at least " + format_number(kMapMinSide));
    check_png_pixels(page, "width");
    return page;
  }
  const auto name = query_choice(req, "paper", {"a4", "a3"}, "a3");
  const bool portrait = query_choice(req, "orientation", {"landscape", "portrait"}, "landscape") == "portrait";
  for (const auto& p : kPapers)
    if (name == p.name) set_paper(page, p, portrait, dpi);
  check_png_pixels(page, "dpi");
  return page;
}

std::string render_map(const map_export::MapScene& scene, const MapPage& page) {
  const auto drawing = map_export::draw_map(scene, page.page_width, page.page_height);
  switch (page.format) {
    case MapFormat::svg: return map_export::write_svg(drawing, {page.svg_width, page.svg_height});
    case MapFormat::pdf: return map_export::render_pdf(drawing, page.out_width, page.out_height);
    case MapFormat::png:
      return map_export::render_png(drawing, static_cast<int>(page.out_width), static_cast<int>(page.out_height));
  }
  return {};
}

Response serve_map(MetroService& metro, const Request& req, MapFormat format) {
  const auto page = parse_map_page(req, format);
  const auto params = parse_layout_query(req);
  auto data = metro.data_for(req.param("id"));
  if (data->graph.edges.empty()) throw ApiError(422, "empty_network", "id: the city has no metro edges to draw", "id");
  const auto started = Clock::now();
  bool cached = false;
  const auto layout = metro.layout_for(*data, params, &cached);
  const double layout_ms = ms_since(started);
  const auto render_started = Clock::now();
  const auto scene = scene_from_layout(nlohmann::json::parse(layout->body), data->city->info.name);
  Response r;
  r.content_type = map_content_type(format);
  r.body = render_map(scene, page);
  r.cacheable = true;
  char timing[96];
  std::snprintf(timing, sizeof timing, "layout;dur=%.2f, render;dur=%.2f", layout_ms, ms_since(render_started));
  r.headers.emplace_back("Server-Timing", timing);
  r.headers.emplace_back("X-Result-Cache", cached ? "hit" : "miss");
  const std::string file = data->city->info.id + "-metro" + (page.paper.empty() ? "" : "-" + page.paper) + "." +
                           map_extension(format);
  r.headers.emplace_back("Content-Disposition", "inline; filename=\"" + file + "\"");
  // An SVG opened on its own is a document: it may style itself, nothing more (no scripts).
  if (format == MapFormat::svg) r.headers.emplace_back("Content-Security-Policy", "default-src 'none'; style-src 'unsafe-inline'");
  return r;
}

}  // namespace tourmap::api
