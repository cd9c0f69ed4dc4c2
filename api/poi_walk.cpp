#include "poi_walk.hpp"

#include "geojson.hpp"
#include "params.hpp"
#include "routes.hpp"
#include "schematic_roads.hpp"

#include "walk/station_walk.hpp"
#include "util/elapsed.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <unordered_map>

namespace tourmap::api {
namespace {

using util::Clock;
using util::ms_since;

constexpr double kWalkKmh = 4.8;  // minutes = distance / (4.8 km/h)
// POI ids in the store are at most this long; a longer one names no POI.
constexpr std::size_t kMaxPoiIdBytes = 512;

// To 1/per of a unit (per: 10 for decimetres, 1e6 for microdegrees), printed without float noise.
double rounded(double v, double per) { return std::round(v * per) / per; }

nlohmann::json lonlat_json(geo::LonLat p) { return nlohmann::json::array({rounded(p.lon, 1e6), rounded(p.lat, 1e6)}); }
nlohmann::json layout_json(geo::XY p) { return nlohmann::json::array({rounded(p.x, 1e3), rounded(p.y, 1e3)}); }

const model::Poi* find_poi(const model::City& city, const std::string& id) {
  if (id.size() > kMaxPoiIdBytes) return nullptr;
  for (const auto& p : city.pois)
    if (p.id == id) return &p;
  return nullptr;
}

ApiError no_road_network(const model::City& city) {
  return ApiError(409, "no_road_network",
                  "road_network: the city '" + city.info.id + "' (" + city.info.name +
                      ") has no road network to walk on (GET /api/v1/cities/" + city.info.id +
                      " gives road_network null); import one with its id or covering at least half its stations",
                  "road_network");
}

// The layout position of every network node from the layout's answer: stations from their
// features, junctions from the ends of the edges' paths (a path runs from its edge's `from`
// node to its `to` node, metro/layout_graph.hpp).
std::vector<std::optional<geo::XY>> layout_nodes(const model::MetroNetwork& net, const std::string& body) {
  std::unordered_map<std::string, std::size_t> index;
  for (std::size_t v = 0; v < net.nodes.size(); ++v) index.emplace(net.nodes[v].id, v);
  std::vector<std::optional<geo::XY>> out(net.nodes.size());
  const auto set = [&](const nlohmann::json& id, const nlohmann::json& c) {
    const auto it = index.find(id.get<std::string>());
    if (it != index.end() && !out[it->second]) out[it->second] = geo::XY{c[0].get<double>(), c[1].get<double>()};
  };
  const auto doc = nlohmann::json::parse(body);
  for (const auto& f : doc.at("stations").at("features")) set(f.at("id"), f.at("geometry").at("coordinates"));
  for (const auto& f : doc.at("edges").at("features")) {
    const auto& c = f.at("geometry").at("coordinates");
    if (c.empty()) continue;
    set(f.at("properties").at("from"), c.front());
    set(f.at("properties").at("to"), c.back());
  }
  return out;
}

}  // namespace

PoiWalkService::PoiWalkService(Catalog& catalog, MetroService& metro, PoiWalkLimits limits)
    : catalog_(catalog), metro_(metro), graphs_(limits.graph_cache_bytes), warps_(limits.warp_cache_entries) {}

std::shared_ptr<const walk::WalkGraph> PoiWalkService::graph_for(const RoadNetworkEntry& roads) {
  const auto key = roads.info.id + "@" + std::to_string(roads.info.version);
  if (auto hit = graphs_.get(key)) return *hit;
  auto graph = graph_flight_.run(key, [&] { return walk::build_walk_graph(roads.net); });
  graphs_.put(key, graph, graph->bytes());
  return graph;
}

std::shared_ptr<const LayoutWarp> PoiWalkService::warp_for(const CityMetroData& data) {
  if (data.graph.edges.empty()) return nullptr;
  std::shared_ptr<const CityLayout> layout;
  try {
    bool cached = false;
    layout = metro_.layout_for(data, LayoutRequest{}, &cached);  // as GET /layout without parameters
  } catch (const ApiError& e) {
    if (e.status == 413 || e.status == 422) return nullptr;  // no layout for this network
    throw;
  }
  const auto key = data.key + ":default";
  // A layout improved in the background replaces the cached one: the warp follows it.
  if (auto hit = warps_.get(key); hit && (*hit)->source.lock() == layout) return *hit;
  const auto nodes = layout_nodes(data.city->metro, layout->body);
  std::vector<geo::XY> from, to;
  std::size_t missing = 0;
  for (std::size_t v = 0; v < nodes.size() && v < data.graph.pos.size(); ++v) {
    if (!nodes[v]) {
      ++missing;
      continue;
    }
    from.push_back(data.graph.pos[v]);
    to.push_back(*nodes[v]);
  }
  auto warp = std::make_shared<const LayoutWarp>(LayoutWarp{layout, data.projection, metro::Warp(from, to), missing});
  warps_.put(key, warp);
  return warp;
}

Response PoiWalkService::handle(const Request& req) {
  const auto started = Clock::now();
  const auto k = static_cast<std::size_t>(query_int(req, "stations", 1, 5, 3));
  const double max_m = query_number(req, "max_m", 100, 5000, 2000);
  const auto data = metro_.data_for(req.param("id"));  // 404 naming `id` when there is no such city
  const auto& city = *data->city;
  const auto* poi = find_poi(city, req.param("poi"));
  if (!poi) throw not_found("poi", "POI", req.param("poi"));
  const auto roads_id = covering_road_network(catalog_, city);
  if (roads_id.empty()) throw no_road_network(city);
  const auto roads = catalog_.road_network(roads_id);
  if (!roads) throw no_road_network(city);  // deleted meanwhile
  const auto graph = graph_for(*roads);

  // The stations, one group per station id (its platforms or stops).
  walk::WalkQuery q;
  q.from = poi->pos;
  q.k = k;
  q.max_m = max_m;
  std::vector<std::uint32_t> node_of;  // target -> network node
  std::map<std::string, std::uint32_t> group_of;
  const auto& nodes = city.metro.nodes;
  for (std::uint32_t v = 0; v < nodes.size(); ++v) {
    if (!nodes[v].is_station()) continue;
    const auto group = group_of.try_emplace(nodes[v].station_id, static_cast<std::uint32_t>(group_of.size())).first->second;
    q.targets.push_back({nodes[v].pos, group});
    node_of.push_back(v);
  }
  const auto search_started = Clock::now();
  const auto result = walk::nearest_walks(*graph, q);
  const double search_ms = ms_since(search_started);

  const auto warp = warp_for(*data);
  const auto to_layout = [&](geo::LonLat p) { return warp->warp(geo::project(warp->projection, p)); };
  nlohmann::json walks = nlohmann::json::array();
  for (const auto& w : result.walks) {
    const auto& station = nodes[node_of[w.target]];
    nlohmann::json path = nlohmann::json::array(), path_layout = nlohmann::json::array();
    for (const auto& p : w.path) {
      path.push_back(lonlat_json(p));
      if (warp) path_layout.push_back(layout_json(to_layout(p)));
    }
    walks.push_back({{"station", {{"id", station.id}, {"station_id", station.station_id}, {"name", station.name}}},
                     {"distance_m", rounded(w.distance_m, 10)},
                     {"straight_m", rounded(w.straight_m, 10)},
                     {"minutes", rounded(w.distance_m / (kWalkKmh * 1000.0 / 60.0), 10)},
                     {"path", std::move(path)},
                     {"path_layout", warp ? std::move(path_layout) : nlohmann::json(nullptr)}});
  }
  const auto at = position(poi->pos);  // as GET .../pois gives it
  nlohmann::json poi_json = {{"id", poi->id}, {"name", poi->name}, {"lon", at[0]}, {"lat", at[1]}};
  poi_json["layout"] = warp ? layout_json(to_layout(poi->pos)) : nlohmann::json(nullptr);
  poi_json["road_m"] = result.from_snapped ? nlohmann::json(rounded(result.from_snap_m, 10)) : nlohmann::json(nullptr);
  nlohmann::json attribution = nlohmann::json::array();
  if (!roads->info.attribution.empty()) attribution.push_back(roads->info.attribution);
  if (!city.info.attribution.empty() && city.info.attribution != roads->info.attribution)
    attribution.push_back(city.info.attribution);
  const nlohmann::json body = {
      {"city", city.info.id},
      {"version", city.info.version},
      {"road_network", {{"id", roads->info.id}, {"version", roads->info.version}}},
      {"poi", std::move(poi_json)},
      {"params", {{"stations", k}, {"max_m", max_m}, {"speed_kmh", kWalkKmh}}},
      {"layout_frame", warp ? nlohmann::json("layout") : nlohmann::json(nullptr)},
      {"walks", std::move(walks)},
      {"search", {{"candidates", result.candidates}, {"settled", result.settled}}},
      {"attribution", std::move(attribution)}};
  Response r = json_response(body);
  r.cacheable = true;  // no max-age: revalidated, so a new import or improved layout shows at once
  char timing[96];
  std::snprintf(timing, sizeof timing, "compute;dur=%.2f, search;dur=%.3f", ms_since(started), search_ms);
  r.headers.emplace_back("Server-Timing", timing);
  return r;
}

void add_poi_walk_route(Router& router, AppContext& ctx) {
  auto service = std::make_shared<PoiWalkService>(ctx.catalog, ctx.metro);
  router.add("GET", "/api/v1/cities/{id}/pois/{poi}/walk", Exec::heavy,
             [service](Request& req) { return service->handle(req); });
}

}  // namespace tourmap::api
