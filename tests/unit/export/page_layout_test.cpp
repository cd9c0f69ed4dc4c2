#include "export/page_layout.hpp"

#include "export/line_sort.hpp"
#include "metro/label_font.hpp"
#include "export_test_scene.hpp"

#include <gtest/gtest.h>

namespace tourmap::map_export {
namespace {

using testing::small_scene;

bool inside(const Box& outer, const Box& inner) {
  return inner.x0 >= outer.x0 - 1e-6 && inner.y0 >= outer.y0 - 1e-6 && inner.x1 <= outer.x1 + 1e-6 &&
         inner.y1 <= outer.y1 + 1e-6;
}

bool overlap(const Box& a, const Box& b) { return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1; }

TEST(ExportFit, PointsFillTheBoxAtTheLargestScaleCentred) {
  const Box box{0, 0, 200, 100};
  auto fit = fit_items({{{0, 0}}, {{10, 10}}}, box);
  EXPECT_NEAR(fit.scale, 10, 1e-6);
  const auto a = to_page(fit, {0, 0}), b = to_page(fit, {10, 10});
  EXPECT_NEAR(a.x, 50, 1e-6);   // centred across
  EXPECT_NEAR(a.y, 100, 1e-6);  // y up in the layout, down on the page
  EXPECT_NEAR(b.x, 150, 1e-6);
  EXPECT_NEAR(b.y, 0, 1e-6);
}

TEST(ExportFit, ReachInPixelsIsKeptInsideTheBox) {
  const Box box{0, 0, 200, 100};
  auto fit = fit_items({{{0, 0}, -10, -10, 10, 10}, {{10, 10}, -10, -10, 10, 10}}, box);
  EXPECT_NEAR(fit.scale, 8, 1e-6);  // (100 - 20) / 10
  // A label reaching 50 px east of the east point: the scale across shrinks to (200 - 60) / 10.
  fit = fit_items({{{0, 0}}, {{10, 0}, 0, -5, 50, 5}}, box);
  EXPECT_NEAR(fit.scale, 15, 1e-6);
  EXPECT_NEAR(to_page(fit, {10, 0}).x + 50, 200, 1e-6);
  // Wider than the box whatever the scale: the points alone.
  fit = fit_items({{{0, 0}, -300, 0, 300, 0}, {{10, 0}}}, box);
  EXPECT_NEAR(fit.scale, 20, 1e-6);
}

TEST(ExportFit, OnePointFitsAtAnyScale) {
  auto fit = fit_items({{{5, 5}, -3, -3, 3, 3}}, {0, 0, 100, 100});
  EXPECT_GT(fit.scale, 1e6);
  EXPECT_NEAR(to_page(fit, {5, 5}).x, 50, 1e-3);
}

TEST(ExportPage, NamesComeFromTheLargestScaleAtOrBelowThePages) {
  auto scene = small_scene();
  // 300 units across a page of ~1100 px: about 3.5 px per unit, above both label scales.
  auto page = layout_page(scene, 1200, 800);
  EXPECT_GT(page.fit.scale, 0.5);
  EXPECT_EQ(page.label_scale, 1);
  const double s = page.fit.scale;
  // The larger placement is made for more than the page's scale: the smaller one.
  scene.label_scales[0].px_per_unit = 0.5 * s;
  scene.label_scales[1].px_per_unit = 1.5 * s;
  page = layout_page(scene, 1200, 800);
  EXPECT_EQ(page.label_scale, 0);
  EXPECT_GE(page.fit.scale, scene.label_scales[0].px_per_unit);
  // Below the smallest scale: no names, and the map larger without them.
  scene.label_scales[0].px_per_unit = 1.2 * s;
  page = layout_page(scene, 1200, 800);
  EXPECT_EQ(page.label_scale, -1);
  EXPECT_GT(page.fit.scale, s);
}

TEST(ExportPage, TheNamesChosenFitOnThePage) {
  const auto scene = small_scene();
  const auto page = layout_page(scene, 1200, 800);
  ASSERT_EQ(page.label_scale, 1);
  for (const auto& l : scene.label_scales[1].labels) {
    const auto p = to_page(page.fit, scene.nodes[l.node].pos);
    EXPECT_TRUE(inside(page.map, {p.x + l.x0, p.y + l.y0, p.x + l.x1, p.y + l.y1})) << scene.nodes[l.node].name;
  }
}

TEST(ExportPage, TitleLegendAndAttributionKeepClearOfTheMap) {
  const auto scene = small_scene();
  for (auto [w, h] : {std::pair{1587.0, 1123.0}, std::pair{600.0, 900.0}, std::pair{400.0, 400.0}}) {
    const auto page = layout_page(scene, w, h);
    const Box whole{0, 0, w, h};
    EXPECT_TRUE(inside(whole, page.map));
    EXPECT_EQ(page.title.text, "Testville");
    EXPECT_LT(page.title.at.y, page.map.y0);
    ASSERT_EQ(page.legend.size(), 2u);
    EXPECT_EQ(scene.lines[page.legend[0].line].label, "U1");  // legend order, not the data's
    for (const auto& e : page.legend) {
      EXPECT_TRUE(inside(whole, e.swatch));
      EXPECT_FALSE(overlap(e.swatch, page.map));
    }
    EXPECT_FALSE(overlap(page.legend[0].swatch, page.legend[1].swatch));
    ASSERT_FALSE(page.attribution.empty());
    for (const auto& line : page.attribution) {
      EXPECT_GT(line.at.y, page.map.y1);
      EXPECT_LE(line.at.y, h);
    }
  }
}

TEST(ExportPage, ALongTitleIsSetSmallerToFit) {
  auto scene = small_scene();
  EXPECT_DOUBLE_EQ(layout_page(scene, 1200, 800).title_px, PageStyle{}.title_px);
  scene.title = "Verkehrsverbund Rhein-Neckar Stadtbahn und S-Bahn Gesamtnetz";
  const auto page = layout_page(scene, 600, 800);
  EXPECT_LT(page.title_px, PageStyle{}.title_px);
  EXPECT_LE(page.title.at.x + metro::label_text_em(scene.title) * page.title_px, 600 - PageStyle{}.margin_px + 1e-6);
  EXPECT_LT(page.title.at.y, page.map.y0);
}

TEST(ExportPage, LegendGoesWhereTheMapGrowsLarger) {
  auto scene = small_scene();
  // A wide network on a wide page: the legend below leaves it more room than one beside it.
  auto page = layout_page(scene, 1600, 700);
  EXPECT_FALSE(page.legend_beside);
  // A tall network: beside.
  for (auto& n : scene.nodes) std::swap(n.pos.x, n.pos.y);
  for (auto& e : scene.edges)
    for (auto& p : e.path) std::swap(p.x, p.y);
  page = layout_page(scene, 1600, 700);
  EXPECT_TRUE(page.legend_beside);
}

TEST(ExportPage, WrapsTextAtSpaces) {
  const auto lines = wrap_text("one two three four five six seven", 10, 60);
  ASSERT_GT(lines.size(), 1u);
  std::string joined;
  for (const auto& l : lines) joined += (joined.empty() ? "" : " ") + l;
  EXPECT_EQ(joined, "one two three four five six seven");
  EXPECT_EQ(wrap_text("", 10, 60).size(), 0u);
  EXPECT_EQ(wrap_text("averyveryverylongword", 10, 20).size(), 1u);
}

TEST(ExportPage, SymbolsFollowTheClientsRule) {
  const auto scene = small_scene();  // mean edge 100 units
  EXPECT_DOUBLE_EQ(symbol_radius_px(scene, 0.1), 3);    // 1 px: the minimum
  EXPECT_DOUBLE_EQ(symbol_radius_px(scene, 0.5), 4);    // 0.08 of 50 px
  EXPECT_DOUBLE_EQ(symbol_radius_px(scene, 10), 8);     // the maximum
}

TEST(ExportLegend, SortsLikeTheClient) {
  EXPECT_LT(compare_labels("U2", "U11"), 0);
  EXPECT_GT(compare_labels("U11", "U2"), 0);
  EXPECT_EQ(compare_labels("u1", "U1"), 0);
  EXPECT_LT(compare_labels("Bakerloo", "central"), 0);
  EXPECT_LT(compare_labels("S1", "S1X"), 0);
  EXPECT_LT(compare_labels("U02", "U3"), 0);
  std::vector<SceneLine> lines = {{"a", "U6", {}}, {"b", "S45", {}}, {"c", "U11", {}}, {"d", "U1", {}}, {"e", "S5", {}}};
  const auto order = legend_order(lines);
  std::vector<std::string> labels;
  for (auto i : order) labels.push_back(lines[i].label);
  EXPECT_EQ(labels, (std::vector<std::string>{"S5", "S45", "U1", "U6", "U11"}));
}

}  // namespace
}  // namespace tourmap::map_export
