#include "metro_layout.hpp"

#include "geojson.hpp"
#include "params.hpp"

#include "util/elapsed.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tourmap::api {
namespace {

constexpr int kLayoutVersion = 17;  // 6: bend reduction, quality.compare (the metric tool's figures); 7: clearance in the bend reduction; 8: detour limit in the router, spacing with cuts, mm coordinates, line order; 9: names on leaders; 10: bends by rounds, names apart between zooms; 11: MIP improvements only as better maps; 12: room for names, symbols 12 px at 75 px; 13: longer leaders, names kept between room rounds; 14: smaller type as the last resort; 15: room for one name at a time; 16: several names moved at once where one is left out; 17: room for one name with a wider reach
using util::Clock;
using util::ms_since;

double round1(double v) { return std::round(v * 10) / 10; }
// Layout coordinates in millimetres: a decimetre bent the short legs of an octilinear path out
// of their direction (a 1-2 m leg by 1-2 degrees, so the metric tool counted it as a bend and
// a piece that is not octilinear); the geographic ones keep decimetres.
double round3(double v) { return std::round(v * 1000) / 1000; }
nlohmann::json xy(geo::XY p) { return nlohmann::json::array({round1(p.x), round1(p.y)}); }
nlohmann::json layout_xy(geo::XY p) { return nlohmann::json::array({round3(p.x), round3(p.y)}); }

RankSource rank_from(const std::string& s, const std::string& field) {
  if (s == "auto") return RankSource::automatic;
  if (s == "data") return RankSource::data;
  if (s == "proxy") return RankSource::proxy;
  if (s == "uniform") return RankSource::uniform;
  throw bad(field, "expected auto, data, proxy or uniform");
}

LayoutRequest::Solver solver_from(const std::string& s) {
  if (s == "auto") return LayoutRequest::Solver::automatic;
  if (s == "fast") return LayoutRequest::Solver::fast;
  if (s == "mip") return LayoutRequest::Solver::mip;
  throw bad("solver", "expected auto, mip or fast");
}

double bounded(double v, const std::string& field, double lo, double hi) {
  if (!std::isfinite(v) || v < lo || v > hi)
    throw bad(field, "must be between " + nlohmann::json(lo).dump() + " and " + nlohmann::json(hi).dump());
  return v;
}

void set_number(LayoutRequest& r, const std::string& key, double v) {
  if (key == "time_limit_s") r.time_limit_s = bounded(v, key, 0.1, 60);
  else if (key == "w_r") r.worth.w_rank = bounded(v, key, 0, 10);
  else if (key == "w_rho") r.worth.w_proximity = bounded(v, key, 0, 10);
  else if (key == "k") r.worth.k_m = bounded(v, key, 10, 100000);
  else if (key == "l_const") r.l_const = bounded(v, key, 1, 1000);
}

nlohmann::json quality_json(const metro::LayoutQuality& q, const metro::CompareMetrics& c) {
  return {{"octilinear_share", q.octilinear_share}, {"bends", q.bends},
          {"compare", {{"bends", c.bends}, {"displacement", c.displacement},
                       {"min_over_mean_edge", c.min_over_mean_edge}, {"octilinear_share", c.octilinear_share}}},
          {"crossings", q.crossings},               {"geo_crossings", q.geo_crossings},
          {"added_crossings", q.added_crossings},
          {"order_violations", q.order_violations}, {"min_edge", q.min_edge},
          {"mean_edge", q.mean_edge},               {"mean_displacement", q.mean_displacement},
          {"min_station_gap", q.min_station_gap},   {"min_station_gap_ratio", q.min_station_gap_ratio}};
}

nlohmann::json solver_json(const metro::SolverReport& s) {
  nlohmann::json out = {{"kind", s.kind}, {"status", s.status}, {"gap", nullptr}};
  if (s.gap) out["gap"] = *s.gap;
  if (s.label_room.status != "not_run") {
    const auto& r = s.label_room;
    out["label_room"] = {{"status", r.status}, {"rooms", r.rooms}, {"unnamed_before", r.unnamed_before},
                         {"unnamed_after", r.unnamed_after}, {"rounds", r.rounds}, {"single_tries", r.single_tries},
                         {"kept", r.kept}};
  }
  if (!s.mip) return out;
  const auto& m = *s.mip;
  nlohmann::json info = {{"status", m.status}};
  if (m.built) {
    info.update({{"columns", m.columns}, {"rows", m.rows}, {"start_objective", m.start_objective},
                 {"build_ms", m.build_ms}, {"time_ms", m.time_ms}});
    if (m.solved) info.update({{"objective", m.objective}, {"gap", m.gap}, {"accepted", m.accepted}});
  }
  if (!m.reason.empty()) info["reason"] = m.reason;
  out["mip"] = std::move(info);
  return out;
}

nlohmann::json bend_reduction_json(const metro::BendReductionReport& b) {
  return {{"chains", b.chains},   {"bends_before", b.bends_before}, {"bends_after", b.bends_after},
          {"reshaped", b.reshaped}, {"moved", b.moved},             {"rounds", b.rounds},
          {"time_ms", b.time_ms},   {"timed_out", b.timed_out}};
}

nlohmann::json spacing_json(const metro::SpacingReport& s) {
  return {{"status", s.status},     {"gap_before", s.gap_before}, {"gap_after", s.gap_after},
          {"rounds", s.rounds},     {"accepted", s.accepted},     {"columns", s.columns},
          {"rows", s.rows},         {"cuts", s.cuts},             {"time_ms", s.time_ms}};
}

nlohmann::json line_order_json(const metro::LineOrderReport& o, double ms) {
  return {{"method", o.method},       {"crossings", o.crossings},   {"separations", o.separations},
          {"heuristic_crossings", o.heuristic_crossings}, {"lower_bound", o.lower_bound}, {"pairs", o.pairs},
          {"time_ms", ms}};
}

double round_px(double v) { return std::round(v * 10) / 10; }

// Station names per zoom (metro/station_labels.hpp). Each label is [station index (into the
// stations' features), x0, y0, x1, y1 (its box), text x, text y (the first line's baseline),
// anchor ("s", "m", "e"), split (byte where the second line begins, 0: one line), size (the
// type's px: font.size_px, or font.small_px for a name that fits in no other way)], in px
// from the station's point, x right and y down; a name set off on a leader has four more
// numbers: the leader from (x, y) at the symbol's rim to (x, y) at the box.
nlohmann::json labels_json(const metro::CityLayoutResult& L, const std::vector<int>& station_index, double metres_per_unit) {
  const metro::LabelStyle style;
  double mean_unit = 0;
  for (const auto& path : L.layout.paths)
    for (std::size_t i = 1; i < path.size(); ++i) mean_unit += std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
  if (!L.layout.paths.empty()) mean_unit /= static_cast<double>(L.layout.paths.size());
  nlohmann::json scales = nlohmann::json::array();
  for (const auto& scale : L.labels) {
    nlohmann::json labels = nlohmann::json::array();
    for (const auto& l : scale.labels) {
      if (station_index[l.node] < 0) continue;
      nlohmann::json label = {station_index[l.node], round_px(l.x0), round_px(l.y0), round_px(l.x1), round_px(l.y1),
                              round_px(l.text_x), round_px(l.text_y), std::string(1, l.anchor), l.split,
                              l.font_px > 0 ? l.font_px : style.font_px};
      if (l.leader)
        for (double v : {l.lx0, l.ly0, l.lx1, l.ly1}) label.push_back(round_px(v));
      labels.push_back(std::move(label));
    }
    scales.push_back({{"mean_edge_px", scale.mean_edge_px},
                      {"px_per_m", scale.px_per_unit / metres_per_unit},
                      {"symbol_px", scale.symbol_px},
                      {"unlabelled", scale.unlabelled},
                      {"leaders", scale.leaders},
                      {"small", scale.small},
                      {"labels", std::move(labels)}});
  }
  return {{"font",
           {{"family", metro::kLabelFontFamily}, {"weight", "bold"}, {"size_px", style.font_px}, {"line_px", style.line_px},
            {"small_px", style.small_font_px}}},
          {"symbol", {{"share", style.symbol_share}, {"min_px", style.symbol_min_px}, {"max_px", style.symbol_max_px}}},
          {"line_spacing_px", style.line_spacing_px},
          {"mean_edge_m", mean_unit * metres_per_unit},
          {"time_ms", L.timing.labels},
          {"scales", std::move(scales)}};
}

// Interests as given: at most kMaxInterests categories, names of at most
// kMaxInterestNameBytes bytes, each once, weights finite in [0, kMaxInterestWeight].
void add_interest(poi::CategoryWeights& out, std::string name, double weight) {
  if (out.size() >= poi::kMaxInterests)
    throw bad("interests", "at most " + std::to_string(poi::kMaxInterests) + " categories");
  if (name.size() > poi::kMaxInterestNameBytes)
    throw bad("interests", "category '" + shown(name) + "' is longer than " +
                               std::to_string(poi::kMaxInterestNameBytes) + " bytes");
  if (!std::isfinite(weight) || weight < 0 || weight > poi::kMaxInterestWeight)
    throw bad("interests", "the weight of '" + shown(name) + "' must be between 0 and 10");
  for (const auto& [seen, w] : out)
    if (seen == name) throw bad("interests", "category '" + shown(name) + "' is named twice");
  out.emplace_back(std::move(name), weight);
}

// GET: "category:weight,category:weight,..." (the last ':' of an entry ends its name; a name
// with a ',' can only be sent in a POST); "" names none.
poi::CategoryWeights parse_interests_text(const std::string& text) {
  poi::CategoryWeights out;
  if (text.empty()) return out;
  std::size_t start = 0;
  while (true) {
    const auto comma = text.find(',', start);
    const auto entry = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const auto colon = entry.rfind(':');
    if (colon == std::string::npos)
      throw bad("interests", "expected category:weight pairs separated by commas, got '" + shown(entry) + "'");
    const auto number = entry.substr(colon + 1);
    char* end = nullptr;
    const double w = std::strtod(number.c_str(), &end);
    if (number.empty() || end != number.c_str() + number.size())
      throw bad("interests", "'" + shown(number) + "' is not a number");
    add_interest(out, entry.substr(0, colon), w);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// POST: {"category": weight, ...}.
poi::CategoryWeights parse_interests_json(const nlohmann::json& v) {
  if (!v.is_object()) throw bad("interests", "expected an object of category: weight");
  poi::CategoryWeights out;
  for (auto it = v.begin(); it != v.end(); ++it) {
    if (!it.value().is_number()) throw bad("interests", "the weight of '" + shown(it.key()) + "' must be a number");
    add_interest(out, it.key(), it.value().get<double>());
  }
  return out;
}

nlohmann::json interests_json(const poi::CategoryWeights& weights) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [id, w] : weights) out[id] = w;
  return out;
}

nlohmann::json points_json(const std::vector<geo::XY>& points) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : points) out.push_back(xy(p));
  return out;
}

}  // namespace

std::string LayoutRequest::canonical() const {
  char buf[256];
  // v: the layout algorithm's version; bump it when results change, so stored layouts renew.
  std::snprintf(buf, sizeof buf, "v=%d lengths=%s solver=%d t=%.3f rank=%d wr=%.6g wrho=%.6g k=%.6g l=%.6g",
                kLayoutVersion, worth_lengths ? "vw" : "uniform", static_cast<int>(solver), time_limit_s, static_cast<int>(rank),
                worth.w_rank, worth.w_proximity, worth.k_m, l_const);
  return buf + interests_key(*this);
}

std::string interests_key(const LayoutRequest& req) {
  auto weights = req.interests_resolved ? req.interests : req.interests_given;
  if (weights.empty()) return {};
  std::sort(weights.begin(), weights.end());
  // JSON: names may hold any character, the key stays unambiguous.
  return " interests=" + interests_json(weights).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void resolve_interests(LayoutRequest& req, const CityMetroData& data) {
  for (const auto& given : req.interests_given) {
    const std::string& id = given.first;  // not a structured binding: clang 14 cannot capture those
    const auto& list = data.categories.list;
    if (std::none_of(list.begin(), list.end(), [&](const poi::CategoryCount& c) { return c.id == id; })) {
      std::string known;
      for (const auto& c : list) known += (known.empty() ? "'" : ", '") + shown(c.id) + "'";
      throw bad("interests", "unknown category '" + shown(id) + "'; " +
                                 (known.empty() ? std::string("the city has no POIs") : "the city's categories are " + known));
    }
  }
  try {
    req.interests = poi::normalise_interests(req.interests_given, data.categories);
  } catch (const std::invalid_argument& e) {
    throw bad("interests", e.what());
  }
  req.interests_resolved = true;
}

std::vector<double> interest_weights(const LayoutRequest& req, const CityMetroData& data) {
  LayoutRequest resolved = req;
  resolve_interests(resolved, data);
  return poi::poi_interest_weights(resolved.interests, data.categories);
}

LayoutRequest parse_layout_query(const Request& req) {
  LayoutRequest r;
  for (const auto& [key, value] : req.query) {
    if (key == "lengths") {
      if (value != "visual-worth" && value != "uniform") throw bad(key, "expected visual-worth or uniform");
      r.worth_lengths = value == "visual-worth";
    } else if (key == "solver") {
      r.solver = solver_from(value);
    } else if (key == "rank") {
      r.rank = rank_from(value, key);
    } else if (key == "time_limit_s" || key == "w_r" || key == "w_rho" || key == "k" || key == "l_const") {
      char* end = nullptr;
      double v = std::strtod(value.c_str(), &end);
      if (value.empty() || end != value.c_str() + value.size()) throw bad(key, "'" + value + "' is not a number");
      set_number(r, key, v);
    } else if (key == "interests") {
      r.interests_given = parse_interests_text(value);
    }
  }
  return r;
}

LayoutRequest parse_layout_body(const nlohmann::json& body) {
  if (!body.is_object()) throw bad("body", "expected a JSON object");
  LayoutRequest r;
  for (auto it = body.begin(); it != body.end(); ++it) {
    const auto& key = it.key();
    const auto& v = it.value();
    if (key == "lengths" || key == "solver" || key == "rank") {
      if (!v.is_string()) throw bad(key, "expected a string");
      auto s = v.get<std::string>();
      if (key == "lengths") {
        if (s != "visual-worth" && s != "uniform") throw bad(key, "expected visual-worth or uniform");
        r.worth_lengths = s == "visual-worth";
      } else if (key == "solver") {
        r.solver = solver_from(s);
      } else {
        r.rank = rank_from(s, key);
      }
    } else if (key == "time_limit_s" || key == "w_r" || key == "w_rho" || key == "k" || key == "l_const") {
      if (!v.is_number()) throw bad(key, "expected a number");
      set_number(r, key, v.get<double>());
    } else if (key == "interests") {
      r.interests_given = parse_interests_json(v);
    } else {
      throw bad(key, "unknown field");
    }
  }
  return r;
}

std::vector<double> poi_worth_geo(const CityMetroData& data, RankSource rank, const metro::WorthParams& params,
                                  const std::vector<double>& poi_weight) {
  check_rank_source(data, rank);
  auto vw = metro::make_visual_worth(data, data.city->pois, rank, params, poi_weight);
  return vw.at_points(data.poi_xy);  // batched: exact within the work budget, else bounded
}

metro::CityLayoutParams layout_params(const CityMetroData& data, const LayoutRequest& req, const MipSolver& mip) {
  metro::CityLayoutParams p;
  p.worth_lengths = req.worth_lengths;
  p.l_const = req.l_const;
  p.rank = req.rank;
  p.worth = req.worth;
  p.solver = req.solver;
  p.poi_weight = interest_weights(req, data);
  p.time_limit_s = req.time_limit_s;
  p.mip = mip;
  p.label_room_ms = req.label_room ? metro::kLabelRoomCpuMs : 0.0;
  return p;
}

std::shared_ptr<const CityLayout> compute_city_layout(const CityMetroData& d, const LayoutRequest& given,
                                                      const MipSolver& mip) {
  auto started = Clock::now();
  LayoutRequest req = given;
  resolve_interests(req, d);
  check_rank_source(d, req.rank);
  auto computed = metro::layout_city(d, d.city->pois, layout_params(d, req, mip));
  auto result = std::make_shared<CityLayout>();
  result->poi_layout = computed.frame.poi_layout;
  result->poi_worth = computed.poi_worth;
  result->poi_outside = computed.frame.poi_outside;
  result->quality = computed.quality;
  result->status = computed.layout.status;
  result->body = layout_body(d, req, computed, started);
  return result;
}

std::string layout_body(const CityMetroData& d, const LayoutRequest& req, const metro::CityLayoutResult& L,
                        Clock::time_point started) {
  const auto& city = *d.city;
  const auto& net = city.metro;
  const auto& frame = L.frame.frame;
  double max_worth = 0;
  for (std::size_t v = 0; v < L.node_worth.size(); ++v)
    if (net.nodes[v].is_station()) max_worth = std::max(max_worth, L.node_worth[v]);
  auto line_ids = [&](const std::vector<std::uint32_t>& idx) {
    nlohmann::json ids = nlohmann::json::array();
    for (auto l : idx) ids.push_back(net.lines[l].id);
    return ids;
  };
  std::vector<std::vector<std::uint32_t>> node_lines(net.nodes.size());
  for (const auto& e : net.edges)
    for (auto l : e.lines)
      for (auto v : {e.from, e.to})
        if (std::find(node_lines[v].begin(), node_lines[v].end(), l) == node_lines[v].end()) node_lines[v].push_back(l);
  nlohmann::json stations = nlohmann::json::array();
  std::vector<int> station_index(net.nodes.size(), -1);  // node -> its feature's index
  for (std::size_t v = 0; v < net.nodes.size(); ++v) {
    const auto& n = net.nodes[v];
    if (!n.is_station()) continue;
    station_index[v] = static_cast<int>(stations.size());
    stations.push_back({{"type", "Feature"},
                        {"id", n.id},
                        {"geometry", {{"type", "Point"}, {"coordinates", layout_xy(L.frame.nodes[v])}}},
                        {"properties", {{"id", n.id},
                                        {"station_id", n.station_id},
                                        {"name", n.name},
                                        {"lines", line_ids(node_lines[v])},
                                        {"worth", max_worth > 0 ? L.node_worth[v] / max_worth : 0.0},
                                        {"geo", xy(d.graph.pos[v])},
                                        {"lonlat", position(n.pos)}}}});
  }
  nlohmann::json edges = nlohmann::json::array();
  for (std::size_t e = 0; e < net.edges.size(); ++e) {
    nlohmann::json coords = nlohmann::json::array(), geo_coords = nlohmann::json::array();
    for (const auto& p : L.layout.paths[e]) coords.push_back(layout_xy(frame.apply(p)));
    for (const auto& p : net.edges[e].geometry) geo_coords.push_back(xy(geo::project(d.projection, p)));
    edges.push_back({{"type", "Feature"},
                     {"geometry", {{"type", "LineString"}, {"coordinates", std::move(coords)}}},
                     {"properties", {{"from", net.nodes[net.edges[e].from].id},
                                     {"to", net.nodes[net.edges[e].to].id},
                                     {"lines", line_ids(net.edges[e].lines)},
                                     {"line_order", line_ids(L.line_order.order[e])},
                                     {"min_length", round1(frame.scale * L.min_length[e])},
                                     {"geo", std::move(geo_coords)}}}});
  }
  double max_poi_worth = 0;
  for (double w : L.poi_worth) max_poi_worth = std::max(max_poi_worth, w);
  nlohmann::json pois = nlohmann::json::array();
  for (std::size_t i = 0; i < city.pois.size(); ++i) {
    const auto& p = city.pois[i];
    nlohmann::json props = {{"id", p.id},
                            {"name", p.name},
                            {"category", p.category},
                            {"worth", max_poi_worth > 0 ? L.poi_worth[i] / max_poi_worth : 0.0},
                            {"station_km", std::round(d.poi_station_km[i] * 1000) / 1000},
                            {"outside", static_cast<bool>(L.frame.poi_outside[i])},
                            {"geo", xy(d.poi_xy[i])},
                            {"lonlat", position(p.pos)}};
    if (!p.image_url.empty()) props["image"] = p.image_url;
    if (!p.url.empty()) props["url"] = p.url;
    if (!p.wikipedia.empty()) props["wikipedia"] = p.wikipedia;
    pois.push_back({{"type", "Feature"},
                    {"id", p.id},
                    {"geometry", {{"type", "Point"}, {"coordinates", xy(L.frame.poi_layout[i])}}},
                    {"properties", std::move(props)}});
  }
  nlohmann::json lines = nlohmann::json::array();
  for (const auto& l : net.lines) lines.push_back(line_json(l));
  nlohmann::json attribution = nlohmann::json::array();
  if (!city.info.attribution.empty()) attribution.push_back(city.info.attribution);
  if (!city.info.poi_attribution.empty()) attribution.push_back(city.info.poi_attribution);
  const auto& report = L.route;
  const auto rank = metro::resolve_rank_source(req.rank, d.has_rank);
  nlohmann::json params = {{"lengths", req.worth_lengths ? "visual-worth" : "uniform"},
                           {"rank", rank == RankSource::data ? "data" : rank == RankSource::proxy ? "proxy" : "uniform"},
                           {"w_r", req.worth.w_rank},
                           {"w_rho", req.worth.w_proximity},
                           {"k", req.worth.k_m},
                           {"l_const", req.l_const},
                           {"time_limit_s", req.time_limit_s}};
  // Only when some category weighs other than 1: default answers stay as they were.
  if (!req.interests.empty()) params["interests"] = interests_json(req.interests);

  nlohmann::json body = {
      {"city", city.info.id},
      {"version", city.info.version},
      {"frame", {{"kind", "city-metres"},
                 {"description", "x east, y north, metres in the city's transverse Mercator projection; the layout "
                                 "is aligned to the geography by a uniform scale and a translation"},
                 {"projection", {{"kind", "transverse_mercator"},
                                 {"lon0", d.projection.origin.lon},
                                 {"lat0", d.projection.origin.lat},
                                 {"k0", 1.0}}},
                 {"layout_units_per_metre", frame.scale != 0 ? 1.0 / frame.scale : 0.0}}},
      {"params", std::move(params)},
      {"stations", {{"type", "FeatureCollection"}, {"features", std::move(stations)}}},
      {"edges", {{"type", "FeatureCollection"}, {"features", std::move(edges)}}},
      {"pois", {{"type", "FeatureCollection"}, {"features", std::move(pois)}}},
      {"mesh", {{"cols", L.frame.mesh_side}, {"rows", L.frame.mesh_side},
                {"geo", points_json(L.frame.mesh.geo)}, {"layout", points_json(L.frame.mesh.layout)}}},
      {"outline", {{"geo", points_json(L.frame.outline.geo)}, {"layout", points_json(L.frame.outline.layout)}}},
      {"lines", std::move(lines)},
      {"quality", quality_json(L.quality, L.compare)},
      {"solver", solver_json(L.solver)},
      {"line_order", line_order_json(L.line_order.report, L.timing.line_order)},
      {"labels", labels_json(L, station_index, frame.scale)},
      {"fast_path", {{"status", report.timed_out ? "time_limit" : report.failed ? "incomplete" : report.overlapping ? "overlapping" : "ok"},
                     {"time_ms", L.timing.fast},
                     {"prelayout_ms", L.timing.prelayout},
                     {"chains", report.chains},
                     {"contracted_nodes", report.contracted_nodes},
                     {"ripups", report.ripups},
                     {"overlapping", report.overlapping},
                     {"crossing_routes", report.crossing_routes},
                     {"failed", report.failed},
                     {"attempt", report.attempt},
                     {"bend_reduction", bend_reduction_json(L.bends)},
                     {"spacing", spacing_json(L.spacing)}}},
      {"timing_ms", {{"visual_worth", L.timing.visual_worth}, {"layout", L.timing.layout}, {"warp", L.timing.warp},
                     {"total", ms_since(started)}}},
      {"attribution", std::move(attribution)}};
  return body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace tourmap::api
