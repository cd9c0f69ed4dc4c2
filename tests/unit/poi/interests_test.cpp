// Interests (core/poi/interests.hpp): categories with counts, the canonical form (equivalent
// vectors share it), refusals, and per-POI weights.
#include "poi/interests.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace tourmap::poi {
namespace {

std::vector<model::Poi> pois_of(std::initializer_list<const char*> categories) {
  std::vector<model::Poi> out;
  for (const char* c : categories) {
    model::Poi p;
    p.id = std::to_string(out.size());
    p.category = c;
    out.push_back(p);
  }
  return out;
}

TEST(PoiInterests, CategoriesWithCountsByName) {
  const auto cats = poi_categories(pois_of({"park", "museum", "park", "Art", "", "park"}));
  ASSERT_EQ(cats.list.size(), 4u);
  EXPECT_EQ(cats.list[0].id, "");
  EXPECT_EQ(cats.list[1].id, "Art");
  EXPECT_EQ(cats.list[2].id, "museum");
  EXPECT_EQ(cats.list[3].id, "park");
  EXPECT_EQ(cats.list[3].count, 3u);
  EXPECT_EQ(cats.list[2].count, 1u);
  EXPECT_EQ(cats.of_poi, (std::vector<std::uint32_t>{3, 2, 3, 1, 0, 3}));
}

TEST(PoiInterests, CanonicalFormIsSharedByEquivalentVectors) {
  const auto cats = poi_categories(pois_of({"art", "food", "park"}));
  const CategoryWeights a = {{"park", 0.5}, {"art", 2}};
  const CategoryWeights b = {{"art", 2}, {"park", 0.5}};
  const CategoryWeights c = {{"art", 4}, {"park", 1}, {"food", 2}};  // a scaled by 2, food named
  const auto canonical = normalise_interests(a, cats);
  EXPECT_EQ(canonical, (CategoryWeights{{"food", 0.5}, {"park", 0.25}}));
  EXPECT_EQ(normalise_interests(b, cats), canonical);
  EXPECT_EQ(normalise_interests(c, cats), canonical);
  EXPECT_EQ(normalise_interests(canonical, cats), canonical);  // idempotent
  // All ones, all the same, or nothing: the paper's worth.
  EXPECT_TRUE(normalise_interests({}, cats).empty());
  EXPECT_TRUE(normalise_interests({{"art", 1}, {"park", 1}}, cats).empty());
  EXPECT_TRUE(normalise_interests({{"art", 3}, {"park", 3}, {"food", 3}}, cats).empty());
  // Rounded to 3 decimals of the maximum.
  EXPECT_EQ(normalise_interests({{"art", 3}}, cats), (CategoryWeights{{"food", 0.333}, {"park", 0.333}}));
  EXPECT_EQ(normalise_interests({{"art", 10}, {"food", 0.004}}, cats), (CategoryWeights{{"food", 0.0}, {"park", 0.1}}));
}

TEST(PoiInterests, Refusals) {
  const auto cats = poi_categories(pois_of({"art", "park"}));
  EXPECT_THROW(normalise_interests({{"arts", 1}}, cats), std::invalid_argument);
  try {
    normalise_interests({{"arts", 1}}, cats);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'art', 'park'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(normalise_interests({{"art", 1}, {"art", 2}}, cats), std::invalid_argument);
  EXPECT_THROW(normalise_interests({{"art", -1}}, cats), std::invalid_argument);
  EXPECT_THROW(normalise_interests({{"art", 10.5}}, cats), std::invalid_argument);
  EXPECT_THROW(normalise_interests({{"art", std::nan("")}}, cats), std::invalid_argument);
  EXPECT_THROW(normalise_interests({{"art", 0}, {"park", 0}}, cats), std::invalid_argument);
  EXPECT_NO_THROW(normalise_interests({{"art", 0}}, cats));  // park keeps 1
}

TEST(PoiInterests, WeightsPerPoi) {
  const auto cats = poi_categories(pois_of({"park", "art", "park", "food"}));
  EXPECT_TRUE(poi_interest_weights({}, cats).empty());
  const auto canonical = normalise_interests({{"park", 0}, {"art", 2}}, cats);
  EXPECT_EQ(poi_interest_weights(canonical, cats), (std::vector<double>{0.0, 1.0, 0.0, 0.5}));
}

}  // namespace
}  // namespace tourmap::poi
