#pragma once
// GET /api/v1/cities/{id}/layout/roads: the streets in the schematic's space (issue 16, item
// 6; the computation is core's, metro/schematic_roads.hpp). The city's octilinear layout (the
// one GET /cities/{id}/layout answers for the same parameters) and a road network of the same
// place give the road map deformed so that every station sits on its street where the
// schematic draws it; polylines in the layout's frame (the stations' coordinates there), by
// road class, with stats and the road data's attribution.
//
// Which road network: ?roads=ID; else the one with the city's id; else the one whose bbox
// holds the most of the city's stations, at least half of them; else 404.
//
// Cached per (city version, road network version, layout parameters, layout): in memory and
// in the store's result cache (kind "layout": a purge of layouts purges these too). The
// layout's own fingerprint is part of the key, so a layout improved in the background
// (MetroService) gives new roads.

#include "catalog.hpp"
#include "http.hpp"
#include "lru_cache.hpp"
#include "metro_service.hpp"
#include "single_flight.hpp"

#include <memory>
#include <string>

namespace tourmap::api {

struct SchematicRoadsLimits {
  // Road edges deformed at most (metro::SchematicRoadsParams::max_edges): beyond it the minor,
  // then the medium roads are left out. Liechtenstein's whole network has 56k edges.
  std::size_t max_edges = 300000;
  std::size_t result_cache_bytes = 64u << 20;
};

// The road network a city's streets come from: the one with the city's id, else the one whose
// bbox holds the most of its stations (at least half); "" when none does. GET /cities/{id}
// tells clients (`road_network`), so they ask for the streets only when there are some.
std::string covering_road_network(Catalog& catalog, const model::City& city);

class SchematicRoadsService {
 public:
  SchematicRoadsService(Catalog& catalog, MetroService& metro, SchematicRoadsLimits limits = {});
  Response handle(const Request& req);

 private:
  std::shared_ptr<const RoadNetworkEntry> road_network_for(const Request& req, const CityMetroData& data);

  Catalog& catalog_;
  MetroService& metro_;
  SchematicRoadsLimits limits_;
  LruCache<std::shared_ptr<const std::string>> results_;
  SingleFlight<std::shared_ptr<const std::string>> flight_;
};

}  // namespace tourmap::api
