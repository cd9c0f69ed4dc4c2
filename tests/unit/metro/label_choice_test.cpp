#include "metro/label_choice.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace tourmap::metro {
namespace {

// Places are numbered in the order they are added; owner and cost per place.
LabelChoiceInput names_with(std::size_t names, std::vector<std::pair<std::uint32_t, double>> places,
                            std::vector<std::pair<int, int>> clashes) {
  LabelChoiceInput in;
  in.names = names;
  for (auto [owner, cost] : places) {
    in.owner.push_back(owner);
    in.cost.push_back(cost);
  }
  in.clashes = std::move(clashes);
  return in;
}

bool clash_taken(const LabelChoiceInput& in, const std::vector<int>& place) {
  return std::any_of(in.clashes.begin(), in.clashes.end(), [&](auto c) {
    return std::find(place.begin(), place.end(), c.first) != place.end() &&
           std::find(place.begin(), place.end(), c.second) != place.end();
  });
}

TEST(LabelChoice, EachNameTakesItsCheapestPlaceWhenNothingClashes) {
  const auto in = names_with(2, {{0, 1.0}, {0, 0.0}, {1, 0.5}, {1, 0.2}}, {});
  const auto out = choose_label_places(in, 1000);
  EXPECT_EQ(out.status, "found");
  EXPECT_EQ(out.place, (std::vector<int>{1, 3}));
}

TEST(LabelChoice, MovesSeveralNamesAtOnceWhereTheGreedyChoiceLeavesOneOut) {
  // A's cheapest place (0) takes C's only place (4); B's cheapest (2) takes A's other (1).
  // Greedily A = 0 leaves C out; the one arrangement naming all three is A = 1, B = 3, C = 4.
  const auto in = names_with(3, {{0, 0.0}, {0, 1.0}, {1, 0.0}, {1, 1.0}, {2, 0.0}}, {{0, 4}, {1, 2}});
  const auto out = choose_label_places(in, 1000);
  EXPECT_EQ(out.status, "found");
  EXPECT_EQ(out.place, (std::vector<int>{1, 3, 4}));
  EXPECT_FALSE(clash_taken(in, out.place));
}

TEST(LabelChoice, SaysWhenNoArrangementNamesEveryone) {
  const auto in = names_with(2, {{0, 0.0}, {1, 0.0}}, {{0, 1}});
  const auto out = choose_label_places(in, 1000);
  EXPECT_EQ(out.status, "none");
  EXPECT_TRUE(out.place.empty());
  // A name without any place: none at once.
  EXPECT_EQ(choose_label_places(names_with(2, {{0, 0.0}}, {}), 1000).status, "none");
}

TEST(LabelChoice, StopsAtItsNodeLimit) {
  // Pigeonholes: 7 names, each may take one of 6 slots, one name per slot. No arrangement
  // exists, and proving it takes far more than 50 nodes.
  constexpr int kNames = 7, kSlots = 6;
  LabelChoiceInput in;
  in.names = kNames;
  for (int n = 0; n < kNames; ++n)
    for (int s = 0; s < kSlots; ++s) {
      in.owner.push_back(static_cast<std::uint32_t>(n));
      in.cost.push_back(s);
    }
  for (int a = 0; a < kNames * kSlots; ++a)
    for (int b = a + 1; b < kNames * kSlots; ++b)
      if (a / kSlots != b / kSlots && a % kSlots == b % kSlots) in.clashes.push_back({a, b});
  const auto out = choose_label_places(in, 50);
  EXPECT_EQ(out.status, "node_limit");
  EXPECT_TRUE(out.place.empty());
  EXPECT_LE(out.nodes, 51u);
  // With one name fewer, it finds an arrangement.
  in.names = kNames - 1;
  in.owner.resize((kNames - 1) * kSlots);
  in.cost.resize((kNames - 1) * kSlots);
  std::erase_if(in.clashes, [&](auto c) { return c.second >= (kNames - 1) * kSlots; });
  const auto found = choose_label_places(in, 100000);
  EXPECT_EQ(found.status, "found");
  EXPECT_FALSE(clash_taken(in, found.place));
}

}  // namespace
}  // namespace tourmap::metro
