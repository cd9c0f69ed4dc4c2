#include "export/cairo_render.hpp"
#include "export/map_drawing.hpp"
#include "export/svg_writer.hpp"
#include "export_test_scene.hpp"

#include <cairo.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <regex>

namespace tourmap::map_export {
namespace {

using testing::small_scene;

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// The PNG's own size, from its IHDR chunk.
std::pair<std::uint32_t, std::uint32_t> png_size(const std::string& png) {
  auto be32 = [&](std::size_t at) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(png[at])) << 24 |
           static_cast<std::uint32_t>(static_cast<unsigned char>(png[at + 1])) << 16 |
           static_cast<std::uint32_t>(static_cast<unsigned char>(png[at + 2])) << 8 |
           static_cast<std::uint32_t>(static_cast<unsigned char>(png[at + 3]));
  };
  return {be32(16), be32(20)};
}

struct PngReader {
  const std::string& data;
  std::size_t at = 0;
};

cairo_status_t read_png(void* closure, unsigned char* out, unsigned int length) {
  auto* r = static_cast<PngReader*>(closure);
  if (r->at + length > r->data.size()) return CAIRO_STATUS_READ_ERROR;
  std::memcpy(out, r->data.data() + r->at, length);
  r->at += length;
  return CAIRO_STATUS_SUCCESS;
}

TEST(ExportSvg, StationNamesAreText) {
  const auto svg = write_svg(draw_map(small_scene(), 1200, 800));
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("viewBox=\"0 0 1200 800\""), std::string::npos);
  EXPECT_NE(svg.find("font-family=\"'DejaVu Sans Condensed'"), std::string::npos);
  EXPECT_EQ(count(svg, "<text class=\"station-label\""), 5u);
  for (const char* name : {">Alpha<", ">Beta &amp; Sons<", ">Gamma<", ">Platz<", ">Delta<", ">Epsilon<"})
    EXPECT_NE(svg.find(name), std::string::npos) << name;
  // Stretched to the width the layout measured, with a halo under the fill.
  EXPECT_NE(svg.find("lengthAdjust=\"spacingAndGlyphs\""), std::string::npos);
  EXPECT_NE(svg.find("paint-order=\"stroke\""), std::string::npos);
  // No glyph outlines: nothing but text carries the names.
  EXPECT_EQ(svg.find("<symbol"), std::string::npos);
  EXPECT_EQ(count(svg, "<text class=\"legend\""), 2u);
  EXPECT_NE(svg.find(">Testville<"), std::string::npos);
  EXPECT_NE(svg.find("Wikidata"), std::string::npos);
  // Each line one path, in its colour.
  EXPECT_NE(svg.find("class=\"line\" fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\" stroke=\"#e2001a\""),
            std::string::npos);
}

TEST(ExportSvg, SizeOnPaperAndEscaping) {
  auto scene = small_scene();
  scene.title = "A <b>\"city\"</b> & \x01more";
  const auto svg = write_svg(draw_map(scene, 1587.4, 1122.5), {"420mm", "297mm"});
  EXPECT_NE(svg.find("width=\"420mm\" height=\"297mm\" viewBox=\"0 0 1587.4 1122.5\""), std::string::npos);
  EXPECT_NE(svg.find("<title>A &lt;b&gt;&quot;city&quot;&lt;/b&gt; &amp; more</title>"), std::string::npos);
  EXPECT_EQ(svg.find('\x01'), std::string::npos);
  EXPECT_EQ(xml_escape("a\tb\n"), "a\tb\n");
}

TEST(ExportPng, HasTheRequestedSizeAndShowsTheMap) {
  const auto d = draw_map(small_scene(), 600, 400);
  const auto png = render_png(d, 1200, 800);  // 2 px per page px (192 dpi)
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(png_size(png), (std::pair<std::uint32_t, std::uint32_t>{1200, 800}));
  PngReader reader{png};
  cairo_surface_t* image = cairo_image_surface_create_from_png_stream(read_png, &reader);
  ASSERT_EQ(cairo_surface_status(image), CAIRO_STATUS_SUCCESS);
  const int w = cairo_image_surface_get_width(image), h = cairo_image_surface_get_height(image);
  const int stride = cairo_image_surface_get_stride(image);
  const unsigned char* px = cairo_image_surface_get_data(image);
  std::size_t red = 0, blue = 0, dark = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint32_t p;
      std::memcpy(&p, px + y * stride + x * 4, 4);
      const int r = (p >> 16) & 0xff, g = (p >> 8) & 0xff, b = p & 0xff;
      red += r == 0xe2 && g == 0 && b == 0x1a;
      blue += r == 0 && g == 0x55 && b == 0xaa;
      dark += r < 60 && g < 60 && b < 70;
    }
  cairo_surface_destroy(image);
  EXPECT_GT(red, 1000u);   // U1's stroke
  EXPECT_GT(blue, 1000u);  // U2's
  EXPECT_GT(dark, 1000u);  // text and outlines in ink
}

TEST(ExportPdf, IsAPdfWithTheLabelsFontEmbedded) {
  const auto pdf = render_pdf(draw_map(small_scene(), 1587.4, 1122.5), 1190.55, 841.89);
  EXPECT_EQ(pdf.rfind("%PDF-1.", 0), 0u);
  EXPECT_NE(pdf.find("%%EOF"), std::string::npos);
  EXPECT_NE(pdf.find("/MediaBox [ 0 0 1190.55 841.89 ]"), std::string::npos);
  // The names are text in an embedded subset of the labels' font (not outlines only).
  EXPECT_TRUE(std::regex_search(pdf, std::regex("/FontName /[A-Z]{6}\\+DejaVuSansCondensed-Bold")));
  EXPECT_NE(pdf.find("/Title (Testville)"), std::string::npos);
}

TEST(ExportPdf, SameDrawingSameBytes) {
  // Cacheable answers need stable bodies (their ETag is the body's hash).
  const auto d = draw_map(small_scene(), 800, 600);
  EXPECT_EQ(render_png(d, 800, 600), render_png(d, 800, 600));
  EXPECT_EQ(render_pdf(d, 600, 450), render_pdf(d, 600, 450));
}

}  // namespace
}  // namespace tourmap::map_export
