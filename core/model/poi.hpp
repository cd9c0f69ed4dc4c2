#pragma once
// A point of interest as tourmap keeps it, whatever the source format.

#include "geo/lonlat.hpp"

#include <optional>
#include <string>
#include <vector>

namespace tourmap::model {

struct Poi {
  std::string id;  // unique within a city
  std::string name;
  geo::LonLat pos;
  std::string category;   // e.g. "museum", "Historic house"; empty when unknown
  std::string image_url;  // representative image, empty when the source has none
  std::string url;        // website
  std::string wikipedia;  // Wikipedia/Wikidata link when the source has one (a popularity proxy)
  std::optional<double> rank;        // source rank (1 = most prominent) when it has one
  std::optional<double> popularity;  // source popularity score when it has one
};

geo::BBox bbox_of(const std::vector<Poi>& pois);

}  // namespace tourmap::model
