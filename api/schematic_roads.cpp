#include "schematic_roads.hpp"

#include "json_out.hpp"
#include "params.hpp"

#include "metro/schematic_roads.hpp"
#include "store/repo.hpp"
#include "util/elapsed.hpp"
#include "util/hash.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tourmap::api {
namespace {

using util::Clock;
using util::ms_since;

// Bump when the answers change, so stored ones renew.
constexpr int kSchematicRoadsVersion = 1;

// The stations as the layout answer gives them: lon/lat and the layout position (what the
// client draws), so the roads match the schematic the client shows.
std::vector<metro::SchematicStation> layout_stations(const std::string& layout_body) {
  const auto doc = nlohmann::json::parse(layout_body);
  std::vector<metro::SchematicStation> out;
  for (const auto& f : doc.at("stations").at("features")) {
    const auto& c = f.at("geometry").at("coordinates");
    const auto& ll = f.at("properties").at("lonlat");
    out.push_back({{ll[0].get<double>(), ll[1].get<double>()}, {c[0].get<double>(), c[1].get<double>()}});
  }
  return out;
}

std::size_t stations_inside(const std::vector<model::MetroNode>& nodes, const geo::BBox& box) {
  std::size_t n = 0;
  for (const auto& node : nodes) n += node.is_station() && box.contains(node.pos);
  return n;
}

// [x,y,x,y,...] rounded to 0.1 layout units (a decimetre at the layout's scale).
void append_flat_xy(std::string& out, const std::vector<geo::XY>& points) {
  out += '[';
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i) out += ',';
    append_number(out, std::round(points[i].x * 10) / 10);
    out += ',';
    append_number(out, std::round(points[i].y * 10) / 10);
  }
  out += ']';
}

double round2(double v) { return std::round(v * 100) / 100; }

nlohmann::json stats_json(const metro::SchematicRoadsStats& s, std::size_t roads) {
  return {{"roads", roads},
          {"road_edges", s.road_edges},
          {"cropped_out_edges", s.cropped_out_edges},
          {"dropped_edges", s.dropped_edges},
          {"classes_kept", s.ranks_kept},
          {"stations", s.stations},
          {"guides", s.guides},
          {"far_stations", s.far_stations},
          {"shared_nodes", s.shared_nodes},
          {"steps", s.steps},
          {"edge_points", s.edge_points},
          {"grid", {{"depth", s.grid_depth}, {"split_vertices", s.split_vertices}, {"quads", s.quads}, {"unknowns", s.unknowns}}},
          {"solver", s.cholesky ? "cholesky" : "cg"},
          {"iterations", s.iterations},
          {"converged", s.converged},
          {"helmert", {{"metres_per_unit", s.helmert_scale},
                       {"rotation_deg", round2(s.helmert_rotation_deg)},
                       {"rms", round2(s.helmert_rms)},
                       {"max", round2(s.helmert_max)}}},
          {"max_guide_error", round2(s.max_guide_error)},
          {"mean_guide_error", round2(s.mean_guide_error)},
          {"max_station_error", round2(s.max_station_error)},
          {"mean_station_error", round2(s.mean_station_error)},
          {"foldovers", s.foldovers},
          {"untangle_left", s.untangle_left},
          {"crossings_added", s.crossings_added},
          {"timing_ms", {{"crop", round2(s.crop_ms)}, {"grid", round2(s.grid_ms)}, {"assembly", round2(s.assembly_ms)},
                         {"factor", round2(s.factor_ms)}, {"solve", round2(s.solve_ms)}, {"place", round2(s.place_ms)},
                         {"crossings", round2(s.crossings_ms)}, {"total", round2(s.total_ms)}}}};
}

// The answer: the roads by class as flat coordinate lists, written straight into the body (a
// country's roads are 100k numbers), then the rest.
std::string roads_body(const CityMetroData& data, const RoadNetworkEntry& roads, const LayoutRequest& params,
                       const metro::SchematicRoadsResult& result) {
  std::string out = "{\"roads\":{";
  for (int rank = 0; rank < metro::kRoadRanks; ++rank) {
    if (rank) out += ',';
    out += '"';
    out += metro::road_rank_name(static_cast<metro::RoadRank>(rank));
    out += "\":[";
    bool first = true;
    for (const auto& road : result.roads) {
      if (static_cast<int>(road.rank) != rank) continue;
      if (!first) out += ',';
      first = false;
      append_flat_xy(out, road.points);
    }
    out += ']';
  }
  out += "},";
  nlohmann::json attribution = nlohmann::json::array();
  if (!roads.info.attribution.empty()) attribution.push_back(roads.info.attribution);
  const nlohmann::json rest = {
      {"city", data.city->info.id},
      {"version", data.city->info.version},
      {"road_network", {{"id", roads.info.id}, {"name", roads.info.name}, {"version", roads.info.version}}},
      {"frame", "layout"},
      {"classes", {"major", "medium", "minor"}},
      {"params", {{"lengths", params.worth_lengths ? "visual-worth" : "uniform"},
                  {"l_const", params.l_const},
                  {"w_r", params.worth.w_rank},
                  {"w_rho", params.worth.w_proximity},
                  {"k", params.worth.k_m},
                  {"time_limit_s", params.time_limit_s}}},
      {"stats", stats_json(result.stats, result.roads.size())},
      {"attribution", std::move(attribution)}};
  const auto text = rest.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  out.append(text, 1, std::string::npos);  // without its opening brace
  return out;
}

}  // namespace

std::string covering_road_network(Catalog& catalog, const model::City& city) {
  // From the store's list (ids and boxes), not the catalog: no road network is loaded for this.
  const auto& nodes = city.metro.nodes;
  std::size_t stations = 0;
  for (const auto& node : nodes) stations += node.is_station();
  std::string best;
  std::size_t best_count = 0;
  auto db = catalog.pool().acquire();
  for (const auto& info : store::list_road_networks(*db)) {
    if (info.id == city.info.id) return info.id;
    const auto n = stations_inside(nodes, info.bbox);
    if (n > best_count) {
      best = info.id;
      best_count = n;
    }
  }
  return best_count == 0 || 2 * best_count < stations ? "" : best;
}

SchematicRoadsService::SchematicRoadsService(Catalog& catalog, MetroService& metro, SchematicRoadsLimits limits)
    : catalog_(catalog), metro_(metro), limits_(limits), results_(limits.result_cache_bytes) {}

std::shared_ptr<const RoadNetworkEntry> SchematicRoadsService::road_network_for(const Request& req,
                                                                                const CityMetroData& data) {
  const auto& city = data.city->info;
  if (const auto* asked = req.query_param("roads")) {
    require_slug(*asked, "road network", "roads");
    auto entry = catalog_.road_network(*asked);
    if (!entry) throw not_found("roads", "road network", *asked);
    return entry;
  }
  const auto best = covering_road_network(catalog_, *data.city);
  if (best.empty())
    throw ApiError(404, "not_found",
                   "id: no road network covers the city '" + city.id + "' (" + city.name +
                       "): import one with its id (PUT /api/v1/roads/" + city.id + ") or covering at least half its stations",
                   "id");
  auto entry = catalog_.road_network(best);
  if (!entry) throw not_found("roads", "road network", best);  // deleted meanwhile
  return entry;
}

Response SchematicRoadsService::handle(const Request& req) {
  const auto started = Clock::now();
  const auto params = parse_layout_query(req);  // the layout's parameters: the roads match it
  auto data = metro_.data_for(req.param("id"));
  if (data->graph.edges.empty()) throw ApiError(422, "empty_network", "id: the city has no metro edges to lay out", "id");
  const auto roads = road_network_for(req, *data);
  bool layout_cached = false;
  const auto layout = metro_.layout_for(*data, params, &layout_cached);

  char version[32];
  std::snprintf(version, sizeof version, "v=%d", kSchematicRoadsVersion);
  const std::string key = "layout-roads:" + data->key + ":" + roads->info.id + "@" + std::to_string(roads->info.version) +
                          ":" + params.canonical() + ":" + util::hex64(util::fnv1a64(layout->body)) + ":" + version;
  bool computed = false;
  std::shared_ptr<const std::string> body;
  if (auto hit = results_.get(key)) {
    body = *hit;
  } else {
    body = flight_.run(key, [&]() -> std::shared_ptr<const std::string> {
      {
        auto db = catalog_.pool().acquire();
        if (auto stored = store::cache_get(*db, key)) return std::make_shared<const std::string>(std::move(stored->body));
      }
      metro::SchematicRoadsParams core;
      core.max_edges = limits_.max_edges;
      metro::SchematicRoadsResult result;
      try {
        result = metro::schematic_roads(roads->net, layout_stations(layout->body), core);
      } catch (const std::invalid_argument& e) {
        throw ApiError(422, "unprocessable", std::string("id: ") + e.what(), "id");
      }
      auto text = std::make_shared<const std::string>(roads_body(*data, *roads, params, result));
      auto db = catalog_.pool().acquire();
      store::cache_put(*db, key, "layout", {"application/json", *text});
      computed = true;
      return text;
    });
    results_.put(key, body, body->size());
  }
  Response r;
  r.body = *body;
  r.cacheable = true;
  r.headers.emplace_back("X-Result-Cache", computed ? "miss" : "hit");
  char timing[48];
  std::snprintf(timing, sizeof timing, "compute;dur=%.2f", ms_since(started));
  r.headers.emplace_back("Server-Timing", timing);
  return r;
}

}  // namespace tourmap::api
