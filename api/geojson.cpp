#include "geojson.hpp"

#include "json_out.hpp"

#include <algorithm>
#include <cmath>

namespace tourmap::api {
namespace {

double round7(double v) { return std::round(v * 1e7) / 1e7; }

nlohmann::json line_string(const std::vector<geo::LonLat>& pts) {
  nlohmann::json coords = nlohmann::json::array();
  for (const auto& p : pts) coords.push_back(position(p));
  return {{"type", "LineString"}, {"coordinates", std::move(coords)}};
}

// Attribution is always a list of strings (empty when the data named no source).
nlohmann::json one_attribution(const std::string& text) {
  return text.empty() ? nlohmann::json::array() : nlohmann::json::array({text});
}

nlohmann::json attribution_list(const model::CityInfo& info) {
  nlohmann::json out = nlohmann::json::array();
  if (!info.attribution.empty()) out.push_back(info.attribution);
  if (!info.poi_attribution.empty()) out.push_back(info.poi_attribution);
  return out;
}

nlohmann::json projection_json(const geo::LocalProjection& proj) {
  return {{"kind", "transverse_mercator"}, {"lon0", proj.origin.lon}, {"lat0", proj.origin.lat}, {"k0", 1.0}};
}

}  // namespace

nlohmann::json position(geo::LonLat p) { return nlohmann::json::array({round7(p.lon), round7(p.lat)}); }

nlohmann::json bbox_json(const geo::BBox& box) {
  if (box.empty()) return nullptr;
  return nlohmann::json::array({round7(box.min_lon), round7(box.min_lat), round7(box.max_lon), round7(box.max_lat)});
}

nlohmann::json city_summary(const model::CityInfo& info) {
  return {{"id", info.id},
          {"name", info.name},
          {"bbox", bbox_json(info.bbox)},
          {"poi_bbox", bbox_json(info.poi_bbox)},
          {"center", position(info.bbox.center())},
          {"projection", projection_json(info.projection)},
          {"counts", {{"stations", info.station_count},
                      {"edges", info.edge_count},
                      {"lines", info.line_count},
                      {"pois", info.poi_count}}},
          {"version", info.version},
          {"attribution", attribution_list(info)}};
}

nlohmann::json line_json(const model::MetroLine& line) {
  return {{"id", line.id},
          {"label", line.label},
          {"color", line.color},
          {"style", {{"casing", line.style.casing}, {"dash", line.style.dash}}}};
}

nlohmann::json road_network_summary(const model::RoadNetworkInfo& info) {
  return {{"id", info.id},
          {"name", info.name},
          {"bbox", bbox_json(info.bbox)},
          {"center", position(info.bbox.center())},
          {"projection", projection_json(info.projection)},
          {"counts", {{"nodes", info.node_count}, {"ways", info.way_count}, {"edges", info.edge_count}}},
          {"version", info.version},
          {"attribution", one_attribution(info.attribution)}};
}

nlohmann::json metro_geojson(const model::City& city, const std::optional<geo::BBox>& bbox) {
  const auto& net = city.metro;
  // Lines serving each station, for labels and colouring.
  std::vector<std::vector<std::uint32_t>> node_lines(net.nodes.size());
  for (const auto& e : net.edges)
    for (auto l : e.lines)
      for (auto n : {e.from, e.to})
        if (std::find(node_lines[n].begin(), node_lines[n].end(), l) == node_lines[n].end()) node_lines[n].push_back(l);

  auto line_ids = [&](const std::vector<std::uint32_t>& idx) {
    nlohmann::json ids = nlohmann::json::array();
    for (auto l : idx) ids.push_back(net.lines[l].id);
    return ids;
  };

  nlohmann::json features = nlohmann::json::array();
  for (std::size_t i = 0; i < net.nodes.size(); ++i) {
    const auto& n = net.nodes[i];
    if (!n.is_station() || (bbox && !bbox->contains(n.pos))) continue;
    features.push_back({{"type", "Feature"},
                        {"id", n.id},
                        {"geometry", {{"type", "Point"}, {"coordinates", position(n.pos)}}},
                        {"properties", {{"kind", "station"},
                                        {"id", n.id},
                                        {"station_id", n.station_id},
                                        {"name", n.name},
                                        {"lines", line_ids(node_lines[i])}}}});
  }
  for (std::size_t i = 0; i < net.edges.size(); ++i) {
    const auto& e = net.edges[i];
    if (bbox) {
      bool touches = false;
      for (std::size_t k = 1; k < e.geometry.size() && !touches; ++k)
        touches = segment_touches(e.geometry[k - 1], e.geometry[k], *bbox);
      if (!touches) continue;
    }
    features.push_back({{"type", "Feature"},
                        {"id", std::string("e").append(std::to_string(i))},
                        {"geometry", line_string(e.geometry)},
                        {"properties", {{"kind", "edge"},
                                        {"from", net.nodes[e.from].id},
                                        {"to", net.nodes[e.to].id},
                                        {"lines", line_ids(e.lines)}}}});
  }
  nlohmann::json lines = nlohmann::json::array();
  for (const auto& l : net.lines) lines.push_back(line_json(l));
  return {{"type", "FeatureCollection"},
          {"city", city.info.id},
          {"version", city.info.version},
          {"lines", std::move(lines)},
          {"attribution", one_attribution(city.info.attribution)},
          {"features", std::move(features)}};
}

nlohmann::json pois_geojson(const model::City& city, const std::optional<geo::BBox>& bbox,
                            const std::vector<std::uint32_t>& selected, const PoiPage& page) {
  nlohmann::json features = nlohmann::json::array();
  std::size_t matched = 0;
  for (auto i : selected) {
    const auto& p = city.pois[i];
    if (bbox && !bbox->contains(p.pos)) continue;
    ++matched;
    if (matched <= page.offset || features.size() >= page.limit) continue;
    nlohmann::json props = {{"id", p.id}, {"name", p.name}, {"category", p.category}};
    if (!p.image_url.empty()) props["image"] = p.image_url;
    if (!p.url.empty()) props["url"] = p.url;
    if (!p.wikipedia.empty()) props["wikipedia"] = p.wikipedia;
    props["rank"] = p.rank ? nlohmann::json(*p.rank) : nlohmann::json(nullptr);
    props["popularity"] = p.popularity ? nlohmann::json(*p.popularity) : nlohmann::json(nullptr);
    features.push_back({{"type", "Feature"},
                        {"id", p.id},
                        {"geometry", {{"type", "Point"}, {"coordinates", position(p.pos)}}},
                        {"properties", std::move(props)}});
  }
  return {{"type", "FeatureCollection"},
          {"city", city.info.id},
          {"version", city.info.version},
          {"matched", matched},
          {"returned", features.size()},
          {"offset", page.offset},
          {"attribution", one_attribution(city.info.poi_attribution)},
          {"features", std::move(features)}};
}

bool segment_touches(geo::LonLat a, geo::LonLat b, const geo::BBox& box) {
  if (box.contains(a) || box.contains(b)) return true;
  double t0 = 0.0, t1 = 1.0;
  double dx = b.lon - a.lon, dy = b.lat - a.lat;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a.lon - box.min_lon, box.max_lon - a.lon, a.lat - box.min_lat, box.max_lat - a.lat};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return false;
      continue;
    }
    double t = q[k] / p[k];
    if (p[k] < 0.0) t0 = std::max(t0, t); else t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  return true;
}

std::string roads_geojson(const RoadNetworkEntry& entry, const std::optional<geo::BBox>& bbox, bool with_nodes,
                          const std::vector<geo::LonLat>* positions) {
  const auto& net = entry.net;
  auto at = [&](std::uint32_t node) { return positions ? (*positions)[node] : net.nodes[node].pos; };
  std::string out;
  out.reserve(net.edges.size() * (with_nodes ? 48 : 32) + net.ways.size() * 96);
  out += R"({"type":"FeatureCollection","network":)";
  append_string(out, entry.info.id);
  out += R"(,"version":)";
  append_integer(out, entry.info.version);
  out += R"(,"attribution":)";
  out += one_attribution(entry.info.attribution).dump();
  out += R"(,"features":[)";
  std::size_t edges_out = 0;
  bool first_feature = true;
  for (const auto& way : net.ways) {
    // Runs of consecutive segments that touch the bbox become one LineString each.
    std::size_t i = 1;
    while (i < way.nodes.size()) {
      auto touches = [&](std::size_t k) {
        return !bbox || segment_touches(net.nodes[way.nodes[k - 1]].pos, net.nodes[way.nodes[k]].pos, *bbox);
      };
      if (!touches(i)) {
        ++i;
        continue;
      }
      std::size_t first = i - 1;
      while (i < way.nodes.size() && touches(i)) ++i;
      edges_out += i - 1 - first;
      if (!first_feature) out += ',';
      first_feature = false;
      out += R"({"type":"Feature","geometry":{"type":"LineString","coordinates":[)";
      for (std::size_t k = first; k < i; ++k) {
        if (k > first) out += ',';
        append_position(out, at(way.nodes[k]));
      }
      out += R"(]},"properties":{"way":)";
      append_integer(out, way.osm_id);
      out += R"(,"highway":)";
      append_string(out, way.highway);
      if (!way.name.empty()) {
        out += R"(,"name":)";
        append_string(out, way.name);
      }
      if (with_nodes) {
        out += R"(,"nodes":[)";
        for (std::size_t k = first; k < i; ++k) {
          if (k > first) out += ',';
          append_integer(out, net.nodes[way.nodes[k]].osm_id);
        }
        out += ']';
      }
      out += "}}";
    }
  }
  out += R"(],"edges":)";
  append_integer(out, static_cast<std::int64_t>(edges_out));
  out += '}';
  return out;
}

nlohmann::json roads_topology(const RoadNetworkEntry& entry) {
  const auto& net = entry.net;
  nlohmann::json coords = nlohmann::json::array(), ids = nlohmann::json::array(), ways = nlohmann::json::array();
  for (const auto& n : net.nodes) {
    auto p = position(n.pos);
    coords.push_back(p[0]);
    coords.push_back(p[1]);
    ids.push_back(n.osm_id);
  }
  for (const auto& w : net.ways) {
    nlohmann::json way = {{"way", w.osm_id}, {"highway", w.highway}, {"nodes", w.nodes}};
    if (!w.name.empty()) way["name"] = w.name;
    ways.push_back(std::move(way));
  }
  return {{"network", entry.info.id},
          {"version", entry.info.version},
          {"bbox", bbox_json(entry.info.bbox)},
          {"positions", std::move(coords)},
          {"node_ids", std::move(ids)},
          {"ways", std::move(ways)},
          {"attribution", one_attribution(entry.info.attribution)}};
}

}  // namespace tourmap::api
