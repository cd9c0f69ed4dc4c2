#include "export/cairo_render.hpp"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

namespace tourmap::map_export {
namespace {

using geo::XY;

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};
using Surface = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using Context = std::unique_ptr<cairo_t, ContextDeleter>;

void check(cairo_status_t status, const char* what) {
  if (status != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(std::string("cairo: ") + what + ": " + cairo_status_to_string(status));
}

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void set_color(cairo_t* cr, const Color& c) { cairo_set_source_rgba(cr, c.r, c.g, c.b, c.a); }

void paint(cairo_t* cr, const Strokes& s) {
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_width(cr, s.width);
  set_color(cr, s.color);
  cairo_new_path(cr);
  for (const auto& path : s.paths) {
    for (std::size_t i = 0; i < path.size(); ++i)
      (i == 0 ? cairo_move_to : cairo_line_to)(cr, path[i].x, path[i].y);
  }
  cairo_stroke(cr);
}

void paint(cairo_t* cr, const RoundedRect& r) {
  cairo_save(cr);
  cairo_translate(cr, r.center.x, r.center.y);
  cairo_rotate(cr, r.angle_deg * std::numbers::pi / 180);
  const double w = r.width / 2, h = r.height / 2, rad = std::min({r.radius, w, h});
  cairo_new_path(cr);
  if (rad <= 0) {
    cairo_rectangle(cr, -w, -h, r.width, r.height);
  } else {
    const double q = std::numbers::pi / 2;
    cairo_arc(cr, w - rad, -h + rad, rad, -q, 0);
    cairo_arc(cr, w - rad, h - rad, rad, 0, q);
    cairo_arc(cr, -w + rad, h - rad, rad, q, 2 * q);
    cairo_arc(cr, -w + rad, -h + rad, rad, 2 * q, 3 * q);
    cairo_close_path(cr);
  }
  set_color(cr, r.fill);
  if (r.stroke_width > 0) {
    cairo_fill_preserve(cr);
    cairo_set_line_width(cr, r.stroke_width);
    set_color(cr, r.stroke);
    cairo_stroke(cr);
  } else {
    cairo_fill(cr);
  }
  cairo_restore(cr);
}

void paint(cairo_t* cr, const Text& t, const std::string& family) {
  cairo_select_font_face(cr, family.c_str(), CAIRO_FONT_SLANT_NORMAL, t.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, t.size_px);
  for (std::size_t i = 0; i < t.lines.size(); ++i) {
    const auto& line = t.lines[i];
    cairo_text_extents_t ext;
    cairo_text_extents(cr, line.c_str(), &ext);
    const double natural = ext.x_advance;
    const double width = i < t.fit_em.size() && t.fit_em[i] > 0 ? t.fit_em[i] * t.size_px : natural;
    const double stretch = natural > 0 ? width / natural : 1;
    const double x = t.anchor == 'm' ? t.at.x - width / 2 : t.anchor == 'e' ? t.at.x - width : t.at.x;
    const double y = t.at.y + static_cast<double>(i) * t.line_px;
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, stretch, 1);
    if (t.halo_px > 0) {
      cairo_new_path(cr);
      cairo_move_to(cr, 0, 0);
      cairo_text_path(cr, line.c_str());
      cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
      cairo_set_line_width(cr, t.halo_px);
      set_color(cr, t.halo);
      cairo_stroke(cr);
    }
    cairo_new_path(cr);
    cairo_move_to(cr, 0, 0);
    set_color(cr, t.fill);
    cairo_show_text(cr, line.c_str());  // real text in a PDF
    cairo_restore(cr);
  }
}

void paint_all(cairo_t* cr, const Drawing& d, double sx, double sy) {
  cairo_scale(cr, sx, sy);
  // Unhinted metrics: a name is as wide at every resolution as the layout measured it.
  cairo_font_options_t* options = cairo_font_options_create();
  cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);
  cairo_font_options_set_hint_style(options, CAIRO_HINT_STYLE_NONE);
  cairo_set_font_options(cr, options);
  cairo_font_options_destroy(options);
  for (const auto& item : d.items) {
    if (const auto* s = std::get_if<Strokes>(&item)) paint(cr, *s);
    else if (const auto* r = std::get_if<RoundedRect>(&item)) paint(cr, *r);
    else if (const auto* t = std::get_if<Text>(&item)) paint(cr, *t, d.font_family);
  }
  check(cairo_status(cr), "drawing");
}

}  // namespace

std::string render_png(const Drawing& d, int width_px, int height_px) {
  if (width_px <= 0 || height_px <= 0 || d.width <= 0 || d.height <= 0) throw std::invalid_argument("render_png: empty size");
  Surface surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_px, height_px));
  check(cairo_surface_status(surface.get()), "image surface");
  {
    Context cr(cairo_create(surface.get()));
    paint_all(cr.get(), d, width_px / d.width, height_px / d.height);
  }
  std::string out;
  check(cairo_surface_write_to_png_stream(surface.get(), append, &out), "png");
  return out;
}

std::string render_pdf(const Drawing& d, double width_pt, double height_pt) {
  if (!(width_pt > 0 && height_pt > 0) || d.width <= 0 || d.height <= 0) throw std::invalid_argument("render_pdf: empty size");
  std::string out;
  {
    Surface surface(cairo_pdf_surface_create_for_stream(append, &out, width_pt, height_pt));
    check(cairo_surface_status(surface.get()), "pdf surface");
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, d.title.c_str());
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "tourmap");
    // No creation date (cairo leaves it out for a date it cannot read): the same map gives
    // the same bytes, so its ETag repeats and a client's If-None-Match gets a 304.
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, "");
    {
      Context cr(cairo_create(surface.get()));
      paint_all(cr.get(), d, width_pt / d.width, height_pt / d.height);
    }
    cairo_surface_finish(surface.get());
    check(cairo_surface_status(surface.get()), "pdf");
  }
  return out;
}

}  // namespace tourmap::map_export
