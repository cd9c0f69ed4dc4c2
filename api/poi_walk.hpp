#pragma once
// GET /api/v1/cities/{id}/pois/{poi}/walk (issue 17, part 4): the nearest stations of a POI by
// walking distance over the city's road network, with the walking paths in lon/lat and warped
// into the default schematic's frame. The search is core's (walk/station_walk.hpp).
//
// The road network is the city's (covering_road_network, as GET /cities/{id} names it); a city
// without one is a 409 naming `road_network`. Parameters: `stations` (1-5, default 3),
// `max_m` (walk cap in metres, 100-5000, default 2000); 400 naming the field otherwise.
//
// Caches: the walking graph per road network version (LRU bounded in bytes; Liechtenstein's is
// ~5 MB and builds in ~0.1 s), and per default layout of a city the warp that carries lon/lat
// into it, rebuilt from the layout's answer (the layout itself is MetroService's, shared with
// GET /layout). A request then costs one bounded Dijkstra search (max_m <= 5 km) and warping
// its paths.

#include "catalog.hpp"
#include "http.hpp"
#include "lru_cache.hpp"
#include "metro_service.hpp"
#include "router.hpp"
#include "single_flight.hpp"

#include "metro/warp.hpp"
#include "walk/walk_graph.hpp"

#include <memory>
#include <string>

namespace tourmap::api {

struct AppContext;

struct PoiWalkLimits {
  std::size_t graph_cache_bytes = 128u << 20;  // walking graphs (least recently used go first)
  std::size_t warp_cache_entries = 64;         // layout warps, one per city version
};

// Geography (the city's projection, metres) -> the default layout's frame, the same warp the
// layout applies to its POIs (metro/city_frame.cpp); with the layout it was made from.
struct LayoutWarp {
  std::weak_ptr<const CityLayout> source;
  geo::LocalProjection projection;
  metro::Warp warp;
  std::size_t missing_nodes = 0;  // network nodes the layout's answer gave no position for
};

class PoiWalkService {
 public:
  PoiWalkService(Catalog& catalog, MetroService& metro, PoiWalkLimits limits = {});
  Response handle(const Request& req);

 private:
  std::shared_ptr<const walk::WalkGraph> graph_for(const RoadNetworkEntry& roads);
  // Null when the city has no default layout (no metro edges, or too many).
  std::shared_ptr<const LayoutWarp> warp_for(const CityMetroData& data);

  Catalog& catalog_;
  MetroService& metro_;
  LruCache<std::shared_ptr<const walk::WalkGraph>> graphs_;
  SingleFlight<std::shared_ptr<const walk::WalkGraph>> graph_flight_;
  LruCache<std::shared_ptr<const LayoutWarp>> warps_;
};

// Registers the route (handlers_metro.cpp calls it).
void add_poi_walk_route(Router& router, AppContext& ctx);

}  // namespace tourmap::api
