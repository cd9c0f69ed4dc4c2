#include "poi/interests.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace tourmap::poi {

PoiCategories poi_categories(const std::vector<model::Poi>& pois) {
  std::map<std::string, std::size_t> counts;
  for (const auto& p : pois) ++counts[p.category];
  PoiCategories out;
  std::map<std::string, std::uint32_t> index;
  for (const auto& [id, count] : counts) {
    index.emplace(id, static_cast<std::uint32_t>(out.list.size()));
    out.list.push_back({id, count});
  }
  out.of_poi.reserve(pois.size());
  for (const auto& p : pois) out.of_poi.push_back(index.at(p.category));
  return out;
}

namespace {

std::size_t find_category(const PoiCategories& categories, const std::string& id) {
  const auto it = std::lower_bound(categories.list.begin(), categories.list.end(), id,
                                   [](const CategoryCount& c, const std::string& key) { return c.id < key; });
  if (it == categories.list.end() || it->id != id) return categories.list.size();
  return static_cast<std::size_t>(it - categories.list.begin());
}

std::string category_names(const PoiCategories& categories) {
  if (categories.list.empty()) return "the city has no POIs";
  std::string out = "the city's categories are ";
  for (std::size_t i = 0; i < categories.list.size(); ++i) {
    if (i) out += ", ";
    out += "'" + categories.list[i].id + "'";
  }
  return out;
}

}  // namespace

CategoryWeights normalise_interests(const CategoryWeights& given, const PoiCategories& categories) {
  if (given.empty()) return {};
  std::vector<double> full(categories.list.size(), 1.0);
  std::vector<bool> named(categories.list.size(), false);
  for (const auto& [id, weight] : given) {
    if (!std::isfinite(weight) || weight < 0 || weight > kMaxInterestWeight)
      throw std::invalid_argument("the weight of '" + id + "' must be between 0 and 10");
    const auto c = find_category(categories, id);
    if (c == categories.list.size())
      throw std::invalid_argument("unknown category '" + id + "'; " + category_names(categories));
    if (named[c]) throw std::invalid_argument("category '" + id + "' is named twice");
    named[c] = true;
    full[c] = weight;
  }
  const double max = *std::max_element(full.begin(), full.end());
  if (!(max > 0)) throw std::invalid_argument("every category weighs 0: nothing would be worth showing");
  CategoryWeights canonical;
  for (std::size_t c = 0; c < full.size(); ++c) {
    const double w = std::round(full[c] / max * 1000) / 1000;
    if (w != 1.0) canonical.emplace_back(categories.list[c].id, w);
  }
  return canonical;
}

std::vector<double> poi_interest_weights(const CategoryWeights& canonical, const PoiCategories& categories) {
  if (canonical.empty()) return {};
  std::vector<double> per_category(categories.list.size(), 1.0);
  for (const auto& [id, weight] : canonical) {
    const auto c = find_category(categories, id);
    if (c < per_category.size()) per_category[c] = weight;
  }
  std::vector<double> out;
  out.reserve(categories.of_poi.size());
  for (auto c : categories.of_poi) out.push_back(per_category[c]);
  return out;
}

}  // namespace tourmap::poi
