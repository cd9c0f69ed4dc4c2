#include "metro/line_styles.hpp"

#include "load/metro_load.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

namespace tourmap::metro {
namespace {

TEST(LineStyles, LabFromSrgb) {
  auto white = lab_from_hex("ffffff");
  ASSERT_TRUE(white);
  EXPECT_NEAR(white->L, 100, 1e-3);
  EXPECT_NEAR(white->a, 0, 1e-2);
  EXPECT_NEAR(white->b, 0, 1e-2);
  auto black = lab_from_hex("#000000");
  ASSERT_TRUE(black);
  EXPECT_NEAR(black->L, 0, 1e-9);
  auto red = lab_from_hex("FF0000");  // sRGB red: L 53.24, a 80.09, b 67.20
  ASSERT_TRUE(red);
  EXPECT_NEAR(red->L, 53.24, 0.01);
  EXPECT_NEAR(red->a, 80.09, 0.01);
  EXPECT_NEAR(red->b, 67.20, 0.01);
  EXPECT_FALSE(lab_from_hex(""));
  EXPECT_FALSE(lab_from_hex("12345"));
  EXPECT_FALSE(lab_from_hex("12345g"));
}

TEST(LineStyles, Ciede2000MatchesThePublishedTestData) {
  // Sharma, Wu, Dalal (2005), table 1: pairs 1, 7, 13, 15, 17, 18, 20.
  struct Pair {
    Lab x, y;
    double expected;
  };
  const Pair pairs[] = {{{50, 2.6772, -79.7751}, {50, 0, -82.7485}, 2.0425},
                        {{50, 0, 0}, {50, -1, 2}, 2.3669},
                        {{50, 2.49, -0.001}, {50, -2.49, 0.0009}, 7.1792},
                        {{50, 2.49, -0.001}, {50, -2.49, 0.0011}, 7.2195},
                        {{50, 2.5, 0}, {73, 25, -18}, 27.1492},
                        {{50, 2.5, 0}, {61, -5, 29}, 22.8977},
                        {{50, 2.5, 0}, {58, 24, 15}, 19.4535}};
  for (const auto& p : pairs) {
    EXPECT_NEAR(delta_e2000(p.x, p.y), p.expected, 1e-4);
    EXPECT_NEAR(delta_e2000(p.y, p.x), p.expected, 1e-4);  // symmetric
  }
  EXPECT_EQ(delta_e2000({50, 10, 10}, {50, 10, 10}), 0.0);
}

double difference(const char* a, const char* b) { return delta_e2000(*lab_from_hex(a), *lab_from_hex(b)); }

TEST(LineStyles, LondonGreensAreCloseInTheDataAndApartInTfLColours) {
  EXPECT_LT(difference("00A166", "00A77E"), kMinColourDifference);  // District, DLR as in the data
  EXPECT_GT(difference("00782A", "00A4A7"), kMinColourDifference);  // in TfL's colours
  EXPECT_GT(difference("00A4A7", "95CDBA"), kMinColourDifference);  // DLR, Waterloo & City
  EXPECT_GT(difference("AE6017", "F15B2E"), kMinColourDifference);  // Bakerloo, Central: apart enough
}

model::MetroNetwork lines_with_colours(const std::vector<std::string>& colours, const std::vector<int>& edges) {
  model::MetroNetwork net;
  for (std::size_t l = 0; l < colours.size(); ++l) {
    // (Appended rather than "l" + to_string: GCC 12 warns falsely about that operator+.)
    net.lines.push_back({std::string("l").append(std::to_string(l)), std::string("L").append(std::to_string(l)), colours[l]});
    for (int e = 0; e < edges[l]; ++e) net.edges.push_back({0, 1, {static_cast<std::uint32_t>(l)}, {}});
  }
  return net;
}

TEST(LineStyles, LinesWithoutAColourGetDistinctOnes) {
  // Five uncoloured lines (Monaco's buses) beside a red one: five valid colours, all unlike each
  // other and the red, so no line needs a casing or a dash; coloured lines keep theirs.
  auto net = lines_with_colours({"e2001a", "", "", "not a colour", "", ""}, {1, 1, 1, 1, 1, 1});
  EXPECT_EQ(assign_missing_colours(net), 5u);
  EXPECT_EQ(net.lines[0].color, "e2001a");
  for (std::size_t i = 0; i < net.lines.size(); ++i) {
    ASSERT_TRUE(lab_from_hex(net.lines[i].color)) << net.lines[i].color;
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_GE(delta_e2000(*lab_from_hex(net.lines[i].color), *lab_from_hex(net.lines[j].color)), kMinColourDifference)
          << net.lines[i].color << " vs " << net.lines[j].color;
  }
  EXPECT_TRUE(assign_line_styles(net).empty());
  EXPECT_EQ(assign_missing_colours(net), 0u);  // all coloured now
}

TEST(LineStyles, WhiteLinesGetACasing) {
  auto net = lines_with_colours({"ffffff", "e2001a", "fff5cc"}, {1, 1, 1});
  EXPECT_TRUE(assign_line_styles(net).empty());
  EXPECT_TRUE(net.lines[0].style.casing);
  EXPECT_TRUE(net.lines[1].style.plain());
  EXPECT_TRUE(net.lines[2].style.casing);
}

TEST(LineStyles, AllButTheBusiestLineOfAGroupGetAStyle) {
  // 0 and 2 identical, 1 far apart; 2 runs on more edges, so 0 gets the casing.
  auto net = lines_with_colours({"815238", "ffd500", "815238"}, {2, 5, 4});
  auto groups = assign_line_styles(net);
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].lines, (std::vector<std::uint32_t>{2, 0}));
  EXPECT_TRUE(net.lines[2].style.plain());
  EXPECT_EQ(net.lines[0].style, (model::LineStyle{true, {}}));
  EXPECT_TRUE(net.lines[1].style.plain());
  EXPECT_EQ(describe_style(net.lines[0].style), "casing");
}

TEST(LineStyles, GroupsChainAndTakeDistinctStyles) {
  // Three near-identical greens (London's District and DLR as in the data, and a third between
  // them), with a tie in edges: the line list order decides.
  auto net = lines_with_colours({"00A166", "00A77E", "00A470", "0000ff"}, {3, 3, 1, 3});
  auto groups = assign_line_styles(net);
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].lines, (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_TRUE(net.lines[0].style.plain());
  EXPECT_EQ(net.lines[1].style, distinct_styles()[0]);
  EXPECT_EQ(net.lines[2].style, distinct_styles()[1]);
  EXPECT_NE(net.lines[1].style, net.lines[2].style);
  EXPECT_TRUE(net.lines[3].style.plain());
  EXPECT_EQ(describe_style(net.lines[2].style), "dash 2-1");
}

TEST(LineStyles, DeterministicAndResettable) {
  auto net = lines_with_colours({"00A166", "00A77E", "", "zzzzzz"}, {1, 1, 1, 1});
  net.lines[3].style = {true, {1, 1}};  // a stale style from before goes
  auto first = assign_line_styles(net);
  auto styled = net;
  auto second = assign_line_styles(net);
  EXPECT_EQ(first.size(), second.size());
  for (std::size_t l = 0; l < net.lines.size(); ++l) EXPECT_EQ(net.lines[l].style, styled.lines[l].style);
  EXPECT_TRUE(net.lines[2].style.plain());  // no colour: no part in the distinction
  EXPECT_TRUE(net.lines[3].style.plain());
  EXPECT_TRUE(assign_line_styles(net, 0).empty());  // 0 turns it off
  for (const auto& l : net.lines) EXPECT_TRUE(l.style.plain());
}

TEST(LineStyles, SharedNetworks) {
  // Berlin: U55 has U5's colour. London as in the data: the DLR is District's green.
  auto berlin = load::load_metro_loom(test::data_file("metro/loom_berlin.json"));
  assign_line_styles(berlin);
  for (const auto& l : berlin.lines) EXPECT_EQ(l.style.casing, l.label == "U55") << l.label;
  auto london = load::load_metro_station_csvs(test::data_file("metro/london.stations.csv"),
                                              test::data_file("metro/london.lines.csv"),
                                              test::data_file("metro/london.connections.csv"));
  assign_line_styles(london);
  for (const auto& l : london.lines)
    EXPECT_EQ(l.style.casing, l.label == "Docklands Light Railway") << l.label;
}

}  // namespace
}  // namespace tourmap::metro
