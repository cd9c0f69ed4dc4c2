#pragma once
// Model -> JSON/GeoJSON (RFC 7946, lon/lat). Coordinates are rounded to 1e-7 degrees (about
// 1 cm), which keeps bodies small without visible loss.

#include "catalog.hpp"

#include "geo/lonlat.hpp"
#include "model/city.hpp"
#include "model/road.hpp"

#include <nlohmann/json.hpp>

#include <optional>

namespace tourmap::api {

nlohmann::json position(geo::LonLat p);
nlohmann::json bbox_json(const geo::BBox& box);

nlohmann::json city_summary(const model::CityInfo& info);

// One entry of a city's line list: {id, label, color, style: {casing, dash}}. The style tells
// lines of close colours apart (metro/line_styles.hpp); {"casing": false, "dash": []} is plain.
nlohmann::json line_json(const model::MetroLine& line);
nlohmann::json road_network_summary(const model::RoadNetworkInfo& info);

// Stations as Points and edges as LineStrings, with the line table and attribution as foreign
// members; `bbox` keeps the stations inside it and the edges that touch it.
nlohmann::json metro_geojson(const model::City& city, const std::optional<geo::BBox>& bbox);

struct PoiPage {
  std::size_t limit = 1000;
  std::size_t offset = 0;
};
nlohmann::json pois_geojson(const model::City& city, const std::optional<geo::BBox>& bbox,
                            const std::vector<std::uint32_t>& selected, const PoiPage& page);

// Ways as LineStrings (split where they leave `bbox`), with OSM way ids, road class, name and,
// when `with_nodes`, the OSM node ids along each line. `positions` (one per node) replaces the
// node positions, e.g. by deformed ones; the bbox still applies to the original positions.
// Written as text directly (see json_out.hpp).
std::string roads_geojson(const RoadNetworkEntry& entry, const std::optional<geo::BBox>& bbox, bool with_nodes,
                          const std::vector<geo::LonLat>* positions = nullptr);

// The network as arrays for clients that redraw it often: node positions (flat lon,lat), node
// ids, and ways as node index lists. Deformation results in "positions" form follow this order.
nlohmann::json roads_topology(const RoadNetworkEntry& entry);

// True when the segment a-b touches the box (Liang-Barsky clipping in lon/lat).
bool segment_touches(geo::LonLat a, geo::LonLat b, const geo::BBox& box);

}  // namespace tourmap::api
