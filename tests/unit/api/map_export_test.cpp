#include "api/map_export.hpp"
#include "api/map_scene_json.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tourmap::api {
namespace {

Request query(std::map<std::string, std::string> q) {
  Request r;
  r.query = std::move(q);
  return r;
}

void expect_field(MapFormat format, std::map<std::string, std::string> q, const std::string& field, int status = 400) {
  try {
    parse_map_page(query(q), format);
    FAIL() << "expected ApiError for " << field;
  } catch (const ApiError& e) {
    EXPECT_EQ(e.field, field) << e.message;
    EXPECT_EQ(e.status, status) << e.message;
  }
}

TEST(MapExportParams, A3At300DpiIsThePrintSize) {
  const auto page = parse_map_page(query({{"paper", "a3"}, {"dpi", "300"}}), MapFormat::png);
  EXPECT_EQ(page.out_width, 4961);
  EXPECT_EQ(page.out_height, 3508);
  EXPECT_NEAR(page.page_width, 1587.4, 0.1);  // laid out in CSS px: names print at 9 pt
  EXPECT_EQ(page.paper, "a3");
}

TEST(MapExportParams, PaperSizesPerFormat) {
  auto page = parse_map_page(query({}), MapFormat::pdf);  // A3 landscape by default
  EXPECT_NEAR(page.out_width, 1190.55, 0.01);
  EXPECT_NEAR(page.out_height, 841.89, 0.01);
  page = parse_map_page(query({{"paper", "a4"}, {"orientation", "portrait"}}), MapFormat::svg);
  EXPECT_EQ(page.svg_width, "210mm");
  EXPECT_EQ(page.svg_height, "297mm");
  EXPECT_NEAR(page.page_height, 1122.5, 0.1);
  page = parse_map_page(query({{"paper", "a4"}}), MapFormat::png);
  EXPECT_EQ(page.out_width, 1123);  // 96 dpi
}

TEST(MapExportParams, WidthAndHeight) {
  auto page = parse_map_page(query({{"width", "1600"}, {"height", "1000"}}), MapFormat::svg);
  EXPECT_EQ(page.page_width, 1600);
  EXPECT_TRUE(page.svg_width.empty());
  page = parse_map_page(query({{"width", "3200"}, {"height", "2000"}, {"dpi", "192"}}), MapFormat::png);
  EXPECT_EQ(page.out_width, 3200);
  EXPECT_EQ(page.page_width, 1600);
  page = parse_map_page(query({{"width", "842"}, {"height", "595"}}), MapFormat::pdf);
  EXPECT_NEAR(page.page_width, 842 * 96.0 / 72, 1e-9);
}

TEST(MapExportParams, BadInputNamesTheField) {
  expect_field(MapFormat::svg, {{"width", "100"}, {"height", "800"}}, "width");
  expect_field(MapFormat::svg, {{"width", "800"}, {"height", "20000"}}, "height");
  expect_field(MapFormat::svg, {{"width", "abc"}, {"height", "800"}}, "width");
  expect_field(MapFormat::svg, {{"width", "nan"}, {"height", "800"}}, "width");
  expect_field(MapFormat::svg, {{"width", "800"}}, "height");
  expect_field(MapFormat::svg, {{"height", "800"}}, "width");
  expect_field(MapFormat::svg, {{"paper", "a3"}, {"width", "800"}}, "width");
  expect_field(MapFormat::svg, {{"paper", "letter"}}, "paper");
  expect_field(MapFormat::svg, {{"orientation", "sideways"}}, "orientation");
  expect_field(MapFormat::svg, {{"width", "800"}, {"height", "800"}, {"orientation", "portrait"}}, "orientation");
  expect_field(MapFormat::svg, {{"dpi", "300"}}, "dpi");
  expect_field(MapFormat::pdf, {{"dpi", "300"}}, "dpi");
  expect_field(MapFormat::png, {{"dpi", "1200"}}, "dpi");
  expect_field(MapFormat::png, {{"dpi", "10"}}, "dpi");
  // A page of 48 CSS px: too small for a map.
  expect_field(MapFormat::png, {{"width", "300"}, {"height", "300"}, {"dpi", "600"}}, "width");
  // Beyond the pixel budget: 413.
  expect_field(MapFormat::png, {{"width", "10000"}, {"height", "10000"}}, "width", 413);
  expect_field(MapFormat::png, {{"paper", "a3"}, {"dpi", "600"}}, "dpi", 413);
  expect_field(MapFormat::pdf, {{"width", "20000"}, {"height", "800"}}, "width");
}

TEST(MapExportScene, ReadFromTheLayoutAnswer) {
  // The layout answer's shape (api/metro_layout.cpp), cut down.
  const auto body = nlohmann::json::parse(R"({
    "lines": [{"id": "u1", "label": "U1", "color": "E2001A"}, {"id": "u2", "label": "U2", "color": "bad"}],
    "stations": {"features": [
      {"geometry": {"coordinates": [0, 0]}, "properties": {"id": "a", "name": "Alpha", "lines": ["u1"]}},
      {"geometry": {"coordinates": [100, 0]}, "properties": {"id": "b", "name": "Beta", "lines": ["u1", "u2"]}}]},
    "edges": {"features": [
      {"geometry": {"coordinates": [[0, 0], [100, 0]]}, "properties": {"from": "a", "to": "b", "lines": ["u1"], "line_order": ["u1"]}},
      {"geometry": {"coordinates": [[100, 0], [100, 50], [150, 100]]}, "properties": {"from": "b", "to": "j", "lines": ["u2", "u1"], "line_order": ["u1", "u2"]}}]},
    "labels": {"font": {"size_px": 12, "line_px": 13}, "symbol": {"share": 0.1, "min_px": 3, "max_px": 8},
               "line_spacing_px": 4, "mean_edge_m": 125,
               "scales": [{"px_per_m": 0.5, "labels": [[1, 5, -7, 40, 7, 5, 4.2, "s", 0, 10, 1, 2, 3, 4], [7, 0, 0, 1, 1, 0, 0, "s", 0, 12]]}]},
    "attribution": ["Network: somebody"]})");
  const auto scene = scene_from_layout(body, "Testville");
  EXPECT_EQ(scene.title, "Testville");
  ASSERT_EQ(scene.lines.size(), 2u);
  EXPECT_EQ(scene.lines[0].color.r, 0xe2);
  EXPECT_EQ(scene.lines[1].color.r, 0x8a);  // no valid colour: the client's grey
  ASSERT_EQ(scene.nodes.size(), 3u);        // two stations and the junction "j"
  EXPECT_FALSE(scene.nodes[2].station);
  EXPECT_DOUBLE_EQ(scene.nodes[2].pos.x, 150);
  ASSERT_EQ(scene.edges.size(), 2u);
  EXPECT_EQ(scene.edges[1].order, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(scene.edges[1].to, 2u);
  EXPECT_DOUBLE_EQ(scene.mean_edge, 125);
  ASSERT_EQ(scene.label_scales.size(), 1u);
  ASSERT_EQ(scene.label_scales[0].labels.size(), 1u);  // the one of a station index beyond them dropped
  EXPECT_EQ(scene.label_scales[0].labels[0].node, 1u);
  EXPECT_DOUBLE_EQ(scene.label_scales[0].labels[0].font_px, 10);  // in the smaller type
  EXPECT_TRUE(scene.label_scales[0].labels[0].leader);
  EXPECT_DOUBLE_EQ(scene.label_scales[0].labels[0].ly1, 4);
  EXPECT_EQ(scene.attribution, (std::vector<std::string>{"Network: somebody"}));
  EXPECT_EQ(parse_line_color("00ff7f").g, 0xff);
}

TEST(MapExportRender, EachFormatsBytes) {
  const auto body = nlohmann::json::parse(R"({
    "lines": [{"id": "u1", "label": "U1", "color": "e2001a"}],
    "stations": {"features": [
      {"geometry": {"coordinates": [0, 0]}, "properties": {"id": "a", "name": "Alpha", "lines": ["u1"]}},
      {"geometry": {"coordinates": [100, 0]}, "properties": {"id": "b", "name": "Beta", "lines": ["u1"]}}]},
    "edges": {"features": [
      {"geometry": {"coordinates": [[0, 0], [100, 0]]}, "properties": {"from": "a", "to": "b", "lines": ["u1"], "line_order": ["u1"]}}]},
    "attribution": []})");
  const auto scene = scene_from_layout(body, "T");
  EXPECT_NE(render_map(scene, parse_map_page(query({{"paper", "a4"}}), MapFormat::svg)).find("<svg"), std::string::npos);
  EXPECT_EQ(render_map(scene, parse_map_page(query({{"paper", "a4"}}), MapFormat::pdf)).rfind("%PDF", 0), 0u);
  EXPECT_EQ(render_map(scene, parse_map_page(query({{"width", "300"}, {"height", "200"}}), MapFormat::png)).substr(1, 3), "PNG");
}

}  // namespace
}  // namespace tourmap::api
