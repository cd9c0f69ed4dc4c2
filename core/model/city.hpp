#pragma once
// A city: its metro network, its POIs and the local projection computed for it.

#include "geo/projection.hpp"
#include "model/metro.hpp"
#include "model/poi.hpp"

#include <cstdint>
#include <string>

namespace tourmap::model {

struct CityInfo {
  std::string id;  // url-safe slug, e.g. "vienna"
  std::string name;
  geo::BBox bbox;                 // of stations and track geometry
  geo::BBox poi_bbox;             // of the POIs (they may reach beyond the metro); empty without POIs
  geo::LocalProjection projection;
  std::string attribution;        // of the metro data; shown wherever it is served
  std::string poi_attribution;    // of the POI data
  std::int64_t version = 0;       // changes with every import touching the city
  std::size_t station_count = 0;
  std::size_t edge_count = 0;
  std::size_t line_count = 0;
  std::size_t poi_count = 0;
};

struct City {
  CityInfo info;
  MetroNetwork metro;
  std::vector<Poi> pois;
};

}  // namespace tourmap::model
