#include "road_context.hpp"

#include "params.hpp"

#include "deform/applications.hpp"

#include <cmath>
#include <numbers>

namespace tourmap::api {
namespace {

// At most this many kinds in one `kinds` list (there are 21 names in all).
constexpr std::size_t kMaxKinds = 32;

bool is_kind_name(std::string_view name) {
  return model::area_kind_named(name) || model::line_kind_named(name) || model::place_kind_named(name);
}

// Lon/lat in metres around the network's centre (equirectangular: for the tolerance only; a
// town-sized extract stays within a fraction of a percent of the true distances).
struct LocalMetres {
  double kx, ky;
  explicit LocalMetres(const model::RoadNetworkInfo& info) {
    constexpr double kMetresPerDegree = 6371008.8 * std::numbers::pi / 180.0;
    const double lat = (info.bbox.min_lat + info.bbox.max_lat) / 2;
    kx = kMetresPerDegree * std::cos(lat * std::numbers::pi / 180.0);
    ky = kMetresPerDegree;
  }
};

double rounded(double degrees) { return std::round(degrees * 1e6) / 1e6; }

// The points simplified to `tolerance_m` (none: all), as a flat rounded [lon, lat, ...] array.
nlohmann::json flat(const std::vector<geo::LonLat>& points, double tolerance_m, const LocalMetres& m, bool ring) {
  nlohmann::json out = nlohmann::json::array();
  std::vector<geo::LonLat> kept;
  if (tolerance_m > 0 && points.size() > 2) {
    std::vector<geo::XY> xy;
    xy.reserve(points.size() + 1);
    for (const auto& p : points) xy.push_back({p.lon * m.kx, p.lat * m.ky});
    if (ring) xy.push_back(xy.front());  // closed, so the ring's first point is a fixed end
    for (const auto& p : deform::simplify_polyline(xy, tolerance_m)) kept.push_back({p.x / m.kx, p.y / m.ky});
    if (ring && kept.size() > 1) kept.pop_back();
  } else {
    kept = points;
  }
  for (const auto& p : kept) {
    out.push_back(rounded(p.lon));
    out.push_back(rounded(p.lat));
  }
  return out;
}

// Shoelace area in square metres.
double area_m2(const std::vector<geo::LonLat>& ring, const LocalMetres& m) {
  double twice = 0;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    twice += (ring[j].lon * m.kx) * (ring[i].lat * m.ky) - (ring[i].lon * m.kx) * (ring[j].lat * m.ky);
  return std::abs(twice) / 2;
}

}  // namespace

ContextQuery parse_context_query(const Request& req) {
  ContextQuery q;
  q.simplify_m = query_number(req, "simplify_m", 0, 1000, 1.0);
  if (const auto* kinds = req.query_param("kinds")) {
    std::size_t start = 0;
    while (start <= kinds->size()) {
      const auto comma = std::min(kinds->find(',', start), kinds->size());
      const std::string name = kinds->substr(start, comma - start);
      if (!is_kind_name(name))
        throw bad("kinds", "unknown kind '" + shown(name) +
                               "' (areas: sea, water, park, forest, farmland, grass, residential, industrial, building;"
                               " lines: river, stream, canal, railway; places: city, town, village, suburb, hamlet,"
                               " neighbourhood, locality, island)");
      if (q.kinds.size() == kMaxKinds) throw too_large("kinds", "at most " + std::to_string(kMaxKinds) + " kinds");
      q.kinds.push_back(name);
      start = comma + 1;
    }
  }
  return q;
}

nlohmann::json road_context_json(const RoadNetworkEntry& entry, const ContextQuery& q) {
  const LocalMetres m(entry.info);
  const auto wanted = [&](std::string_view kind) {
    return q.kinds.empty() || std::find(q.kinds.begin(), q.kinds.end(), kind) != q.kinds.end();
  };
  const double min_area = q.simplify_m * q.simplify_m;
  nlohmann::json areas = nlohmann::json::array(), lines = nlohmann::json::array(), places = nlohmann::json::array();
  std::size_t points = 0;
  for (const auto& a : entry.context.areas) {
    if (!wanted(model::name_of(a.kind)) || a.rings.empty() || area_m2(a.rings[0], m) < min_area) continue;
    nlohmann::json rings = nlohmann::json::array();
    for (const auto& r : a.rings) {
      auto f = flat(r, q.simplify_m, m, true);
      if (f.size() < 6) {
        if (rings.empty()) break;  // the outer ring vanished: so does the area
        continue;                  // a hole too small to show
      }
      points += f.size() / 2;
      rings.push_back(std::move(f));
    }
    if (!rings.empty()) areas.push_back({{"kind", model::name_of(a.kind)}, {"rings", std::move(rings)}});
  }
  for (const auto& l : entry.context.lines) {
    if (!wanted(model::name_of(l.kind))) continue;
    auto f = flat(l.points, q.simplify_m, m, false);
    points += f.size() / 2;
    nlohmann::json line = {{"kind", model::name_of(l.kind)}, {"points", std::move(f)}};
    if (!l.name.empty()) line["name"] = l.name;
    if (l.tunnel) line["tunnel"] = true;
    lines.push_back(std::move(line));
  }
  for (const auto& p : entry.context.places) {
    if (!wanted(model::name_of(p.kind))) continue;
    places.push_back({{"kind", model::name_of(p.kind)},
                      {"name", p.name},
                      {"rank", p.rank},
                      {"pos", {rounded(p.pos.lon), rounded(p.pos.lat)}}});
  }
  return {{"network", entry.info.id},
          {"version", entry.info.version},
          {"attribution", entry.info.attribution},
          {"simplify_m", q.simplify_m},
          {"points", points},
          {"areas", std::move(areas)},
          {"lines", std::move(lines)},
          {"places", std::move(places)}};
}

}  // namespace tourmap::api
