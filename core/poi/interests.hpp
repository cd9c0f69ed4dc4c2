#pragma once
// A tourist's interests (beyond the paper: its future work 6.2): a weight per POI category,
// by which each POI's contribution to the visual worth (eq. 5.1) is multiplied, and so the
// worth edge lengths (eq. 5.4) and the clusters' prominence follow them.
//
// Meaning: the city's categories named get their weight, the others keep 1; only the ratios
// matter. The canonical form is the full vector divided by its largest weight, rounded to 3
// decimals, without the categories at 1 (so at the maximum), sorted by name: equivalent
// vectors (another order, scaled, every category at the same weight) share it, and an empty
// one is the paper's worth. A normalised weight below 0.0005 rounds to 0: the category's POIs
// add nothing to the worth and leave the clusters.

#include "model/poi.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tourmap::poi {

struct CategoryCount {
  std::string id;  // the POIs' category ("" for POIs without one)
  std::size_t count = 0;
};

struct PoiCategories {
  std::vector<CategoryCount> list;    // by id (byte order)
  std::vector<std::uint32_t> of_poi;  // per POI: its category's index in `list`
};

PoiCategories poi_categories(const std::vector<model::Poi>& pois);

// (category, weight) pairs.
using CategoryWeights = std::vector<std::pair<std::string, double>>;

// Bounds on what a request may name (api/ checks them on input, with the field's name).
inline constexpr double kMaxInterestWeight = 10;
inline constexpr std::size_t kMaxInterests = 64;
inline constexpr std::size_t kMaxInterestNameBytes = 64;

// The canonical form of `given` for a city's categories (see above). Throws
// std::invalid_argument for a category the city does not have (the message lists the city's
// categories), a duplicate, a weight outside [0, kMaxInterestWeight] or not finite, or when
// every category would weigh 0.
CategoryWeights normalise_interests(const CategoryWeights& given, const PoiCategories& categories);

// Per POI its category's weight in `canonical` (1 when not named); empty when `canonical` is
// (every weight 1).
std::vector<double> poi_interest_weights(const CategoryWeights& canonical, const PoiCategories& categories);

}  // namespace tourmap::poi
