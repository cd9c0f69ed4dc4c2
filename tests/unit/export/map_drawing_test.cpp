#include "export/map_drawing.hpp"

#include "export/bundle_paths.hpp"
#include "export_test_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tourmap::map_export {
namespace {

using testing::small_scene;

template <class T>
std::vector<const T*> items_of(const Drawing& d, Role role) {
  std::vector<const T*> out;
  for (const auto& item : d.items)
    if (const auto* p = std::get_if<T>(&item); p && p->role == role) out.push_back(p);
  return out;
}

bool same_color(const Color& a, const Color& b) {
  return std::abs(a.r - b.r) < 1e-9 && std::abs(a.g - b.g) < 1e-9 && std::abs(a.b - b.b) < 1e-9;
}

TEST(ExportBundles, OffsetsToTheLeftOfTravel) {
  // Travelling east on the page (y down), left is up.
  auto moved = offset_polyline({{0, 10}, {10, 10}}, 2);
  ASSERT_EQ(moved.size(), 2u);
  EXPECT_NEAR(moved[0].y, 8, 1e-9);
  EXPECT_NEAR(moved[1].x, 10, 1e-9);
  // A right-angle corner is mitred: the corner point moves along both normals.
  moved = offset_polyline({{0, 0}, {10, 0}, {10, 10}}, 1);
  ASSERT_EQ(moved.size(), 3u);
  EXPECT_NEAR(moved[1].x, 11, 1e-9);
  EXPECT_NEAR(moved[1].y, -1, 1e-9);
}

TEST(ExportBundles, LinesSideBySideInTheEdgesOrderAndJoinedThroughStations) {
  // Two lines east along two edges: line 0 left (up), line 1 right (down), 4 px apart.
  const std::vector<BundleEdge> edges = {{0, 1, {{0, 0}, {10, 0}}, {0, 1}}, {1, 2, {{10, 0}, {20, 0}}, {0, 1}}};
  const auto pieces = bundle_pieces(edges, 2, 4);
  ASSERT_EQ(pieces.strokes[0].size(), 2u);
  EXPECT_NEAR(pieces.strokes[0][0][0].y, -2, 1e-9);
  EXPECT_NEAR(pieces.strokes[1][0][0].y, 2, 1e-9);
  // Straight through: the ends meet, nothing to join.
  EXPECT_TRUE(pieces.joins[0].empty());
  // The second edge listed the other way: its order is mirrored, the lines keep their sides,
  // and no join is needed either.
  const std::vector<BundleEdge> flipped = {{0, 1, {{0, 0}, {10, 0}}, {0, 1}}, {2, 1, {{20, 0}, {10, 0}}, {1, 0}}};
  const auto same = bundle_pieces(flipped, 2, 4);
  EXPECT_NEAR(same.strokes[0][1][0].y, -2, 1e-9);
  EXPECT_TRUE(same.joins[0].empty());
  // Swapped sides at node 1: each line joined across it.
  const std::vector<BundleEdge> swapped = {{0, 1, {{0, 0}, {10, 0}}, {0, 1}}, {1, 2, {{10, 0}, {20, 0}}, {1, 0}}};
  const auto crossing = bundle_pieces(swapped, 2, 4);
  EXPECT_EQ(crossing.joins[0].size(), 1u);
  EXPECT_EQ(crossing.joins[1].size(), 1u);
}

TEST(ExportDrawing, DrawsTheNetworkAsTheClientDoes) {
  const auto scene = small_scene();
  const auto page = layout_page(scene, 1200, 800);
  const auto d = draw_map(scene, page);
  EXPECT_EQ(d.width, 1200);
  EXPECT_EQ(d.font_family, "DejaVu Sans Condensed");
  // Casings: one per bundle size, the wider first.
  const auto casings = items_of<Strokes>(d, Role::casing);
  ASSERT_EQ(casings.size(), 2u);
  EXPECT_DOUBLE_EQ(casings[0]->width, 2 * 4 + 3.5);
  EXPECT_DOUBLE_EQ(casings[1]->width, 4 + 3.5);
  // One stroke per line, in its colour.
  const auto lines = items_of<Strokes>(d, Role::line);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_TRUE(same_color(lines[0]->color, color_of(scene.lines[0].color)));
  EXPECT_DOUBLE_EQ(lines[0]->width, 3.5);
  // On the shared edge Beta -> Gamma (east), U2 is first in the order: left of travel, above.
  const double trunk_y = to_page(page.fit, {0, 0}).y;
  bool u2_above = false, u1_below = false;
  for (const auto& path : lines[0]->paths)
    u2_above |= path.size() == 2 && std::abs(path[0].y - (trunk_y - 2)) < 1e-6 && std::abs(path[1].y - (trunk_y - 2)) < 1e-6;
  for (const auto& path : lines[1]->paths)
    u1_below |= path.size() == 2 && std::abs(path[0].y - (trunk_y + 2)) < 1e-6 && std::abs(path[1].y - (trunk_y + 2)) < 1e-6;
  EXPECT_TRUE(u2_above);
  EXPECT_TRUE(u1_below);
}

TEST(ExportDrawing, SymbolsSpanBundlesAndOutlineInterchanges) {
  const auto scene = small_scene();
  const auto page = layout_page(scene, 1200, 800);
  const auto d = draw_map(scene, page);
  const auto symbols = items_of<RoundedRect>(d, Role::station);
  ASSERT_EQ(symbols.size(), 5u);
  const double r = page.symbol_px;
  EXPECT_DOUBLE_EQ(r, 8);  // a mean edge of ~350 px: the largest symbol
  // Alpha: a circle outlined in its line's colour.
  EXPECT_DOUBLE_EQ(symbols[0]->width, 2 * r);
  EXPECT_DOUBLE_EQ(symbols[0]->angle_deg, 0);
  EXPECT_TRUE(same_color(symbols[0]->stroke, color_of(scene.lines[1].color)));
  // Beta: an interchange on a bundle of two running east: a capsule across it, outlined dark.
  EXPECT_DOUBLE_EQ(symbols[1]->width, 2 * r + 4);
  EXPECT_DOUBLE_EQ(symbols[1]->height, 2 * r);
  EXPECT_NEAR(std::fmod(symbols[1]->angle_deg + 360, 180), 90, 1e-9);
  EXPECT_TRUE(same_color(symbols[1]->stroke, MapStyle{}.ink));
  EXPECT_DOUBLE_EQ(symbols[1]->stroke_width, 2.2);
}

TEST(ExportDrawing, NamesWithAHaloAndTheLegendAndAttribution) {
  const auto scene = small_scene();
  const auto d = draw_map(scene, 1200, 800);
  const auto labels = items_of<Text>(d, Role::label);
  ASSERT_EQ(labels.size(), 5u);
  EXPECT_EQ(labels[1]->lines, (std::vector<std::string>{"Beta & Sons"}));
  EXPECT_EQ(labels[2]->lines, (std::vector<std::string>{"Gamma", "Platz"}));  // split at byte 6
  EXPECT_EQ(labels[2]->fit_em.size(), 2u);
  EXPECT_GT(labels[0]->halo_px, 0);
  EXPECT_DOUBLE_EQ(labels[0]->size_px, 12);
  EXPECT_TRUE(labels[0]->bold);
  const auto titles = items_of<Text>(d, Role::title);
  ASSERT_EQ(titles.size(), 1u);
  EXPECT_EQ(titles[0]->lines[0], "Testville");
  EXPECT_EQ(items_of<RoundedRect>(d, Role::legend).size(), 2u);
  const auto legend = items_of<Text>(d, Role::legend);
  ASSERT_EQ(legend.size(), 2u);
  EXPECT_EQ(legend[0]->lines[0], "U1");
  std::string credits;
  for (const auto* t : items_of<Text>(d, Role::attribution)) credits += t->lines[0] + " ";
  EXPECT_NE(credits.find("Testville Transit"), std::string::npos);
  EXPECT_NE(credits.find("Wikidata"), std::string::npos);
}

TEST(ExportDrawing, NamesSetOffOnALeaderGetTheirLeaderUnderTheName) {
  auto scene = small_scene();
  auto& labels = scene.label_scales.back().labels;
  ASSERT_FALSE(labels.empty());
  auto& l = labels[1];
  l.leader = true;
  l.lx0 = 8, l.ly0 = 0, l.lx1 = 20, l.ly1 = -5;
  const auto d = draw_map(scene, 1200, 800);
  const auto leaders = items_of<Strokes>(d, Role::label);
  ASSERT_EQ(leaders.size(), 1u);
  ASSERT_EQ(leaders[0]->paths.size(), 1u);
  const auto& path = leaders[0]->paths[0];
  ASSERT_EQ(path.size(), 2u);
  // From the rim to the box, 12 px right and 5 px up on the page, before (under) every name.
  EXPECT_NEAR(path[1].x - path[0].x, 12, 1e-9);
  EXPECT_NEAR(path[1].y - path[0].y, -5, 1e-9);
  std::size_t leader_at = 0, first_name_at = d.items.size();
  for (std::size_t i = 0; i < d.items.size(); ++i) {
    if (std::get_if<Strokes>(&d.items[i]) && std::get<Strokes>(d.items[i]).role == Role::label) leader_at = i;
    if (const auto* t = std::get_if<Text>(&d.items[i]); t && t->role == Role::label) first_name_at = std::min(first_name_at, i);
  }
  EXPECT_LT(leader_at, first_name_at);
  // Without leaders none is drawn.
  EXPECT_TRUE(items_of<Strokes>(draw_map(small_scene(), 1200, 800), Role::label).empty());
}

}  // namespace
}  // namespace tourmap::map_export
