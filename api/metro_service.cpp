#include "metro_service.hpp"

#include "geojson.hpp"
#include "json_out.hpp"
#include "params.hpp"

#include "poi/active_clusters.hpp"
#include "poi/serialize.hpp"
#include "store/repo.hpp"
#include "util/elapsed.hpp"
#include "util/stop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string_view>

namespace tourmap::api {
namespace {

using util::Clock;
using util::ms_since;

// The compute time goes into a Server-Timing header, not the body: a cacheable body must be the
// same for the same answer, or its ETag never repeats and If-None-Match never gives a 304.
void set_server_timing(Response& r, Clock::time_point started) {
  char text[48];
  std::snprintf(text, sizeof text, "compute;dur=%.2f", ms_since(started));
  r.headers.emplace_back("Server-Timing", text);
}

// A layout read back from the store: the positions the clusters need come from its JSON.
std::shared_ptr<const CityLayout> layout_from_body(std::string body) {
  auto doc = nlohmann::json::parse(body);
  auto l = std::make_shared<CityLayout>();
  for (const auto& f : doc["pois"]["features"]) {
    l->poi_layout.push_back({f["geometry"]["coordinates"][0].get<double>(), f["geometry"]["coordinates"][1].get<double>()});
    l->poi_worth.push_back(f["properties"]["worth"].get<double>());
    l->poi_outside.push_back(f["properties"]["outside"].get<bool>());
  }
  l->status = doc["solver"]["status"].get<std::string>();
  l->body = std::move(body);
  return l;
}

// A layout-space window "x0,y0,x1,y1": 4 finite numbers, min before max. Parsed in place:
// strtod stops at the comma or at the string's terminating NUL, never past the part.
void parse_layout_bbox(const std::string& text, geo::XY& lo, geo::XY& hi) {
  double v[5];
  std::size_t count = 0, start = 0;
  while (count < 5) {  // a fifth number is read only to say there are too many
    const auto comma = text.find(',', start);
    const char* first = text.c_str() + start;
    const char* last = comma == std::string::npos ? text.c_str() + text.size() : text.c_str() + comma;
    char* end = nullptr;
    const double x = std::strtod(first, &end);
    if (first == last || end != last || !std::isfinite(x)) throw bad("bbox", "expected 4 finite numbers");
    v[count++] = x;
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (count != 4) throw bad("bbox", "expected 4 numbers x0,y0,x1,y1");
  if (v[0] > v[2] || v[1] > v[3]) throw bad("bbox", "min must not exceed max");
  lo = {v[0], v[1]};
  hi = {v[2], v[3]};
}

// [x, y] in the layout frame, rounded to 0.1.
void append_xy(std::string& out, geo::XY p) {
  out += '[';
  append_double(out, std::round(p.x * 10) / 10);
  out += ',';
  append_double(out, std::round(p.y * 10) / 10);
  out += ']';
}

// [lon, lat] rounded to 1e-7 degrees (about 1 cm).
void append_lonlat(std::string& out, geo::LonLat p) {
  out += '[';
  append_double(out, std::round(p.lon * 1e7) / 1e7);
  out += ',';
  append_double(out, std::round(p.lat * 1e7) / 1e7);
  out += ']';
}

void append_optional_field(std::string& out, const char* key, const std::string& value) {
  if (value.empty()) return;
  out += ",\"";
  out += key;
  out += "\":";
  append_string(out, value);
}

// Every layout answer says in solver.improvement whether a better one may follow:
// "scheduled" (a background MIP is queued or running; a layout_improved event follows if it
// wins), "none" (nothing follows), "applied" (this is the improved layout). A cached default
// layout without the field has not been decided yet: it is scheduled when served.
//
// The field is written as text right after `"solver":{` rather than by parsing and writing
// the whole body again (hundreds of KB, on every answer while an improvement is pending): the
// body is compact JSON, `solver` is a key of its top-level object only, and inside strings a
// quote is escaped, so the pattern matches nothing else.
constexpr std::string_view kSolverObject = "\"solver\":{";
constexpr std::string_view kImprovementField = "\"improvement\":\"";

// Where the solver object's members start, or npos.
std::size_t solver_members(const std::string& body) {
  const auto at = body.find(kSolverObject);
  return at == std::string::npos ? at : at + kSolverObject.size();
}

// The body's improvement state; empty when it has none.
std::string_view improvement_of(const std::string& body) {
  const auto at = solver_members(body);
  if (at == std::string::npos) return {};
  std::string_view rest(body);
  rest.remove_prefix(at);
  if (!rest.starts_with(kImprovementField)) return {};
  rest.remove_prefix(kImprovementField.size());
  return rest.substr(0, rest.find('"'));
}

// The body with solver.improvement set to `state` (replacing the one it has). A body without
// a solver object (none is made so) is returned as it is.
std::string with_improvement(const std::string& body, std::string_view state) {
  auto at = solver_members(body);
  if (at == std::string::npos) return body;
  auto rest = at;
  if (std::string_view(body).substr(at).starts_with(kImprovementField)) {
    const auto quote = body.find('"', at + kImprovementField.size());  // the old value's end
    if (quote == std::string::npos) return body;
    rest = quote + 1;
    if (rest < body.size() && body[rest] == ',') ++rest;
  }
  std::string out;
  out.reserve(body.size() + 32);
  out.append(body, 0, at).append(kImprovementField).append(state).append("\"");
  if (body[rest] != '}') out += ',';
  out.append(body, rest, std::string::npos);
  return out;
}

std::shared_ptr<const CityLayout> with_body(const CityLayout& layout, std::string body) {
  auto copy = std::make_shared<CityLayout>(layout);
  copy->body = std::move(body);
  return copy;
}

// The cache key of a layout (memory and store).
std::string layout_key(const CityMetroData& data, const LayoutRequest& req) {
  return "layout:" + data.key + ":" + req.canonical();
}

}  // namespace

// The cluster objects of a clusters answer, written straight into the body (json_out.hpp):
// building them as nlohmann::json trees and dumping them took a third of the request's time.
void MetroService::ClusterWriter::append_list(std::string& out, const std::vector<std::uint32_t>& nodes,
                                              const double* prominence) const {
  out += '[';
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (i) out += ',';
    append_cluster(out, nodes[i], prominence[i]);
  }
  out += ']';
}

void MetroService::ClusterWriter::append_cluster(std::string& out, std::uint32_t node, double prominence) const {
  const auto& c = tree.nodes[node];
  out += "{\"center\":";
  if (centers)
    append_lonlat(out, (*centers)[node]);
  else
    append_xy(out, c.center);
  out += ",\"id\":\"c";
  append_integer(out, node);
  out += "\",\"prominence\":";
  append_double(out, prominence);
  out += ",\"representative\":";
  append_representative(out, c.representative);
  out += ",\"size\":";
  append_integer(out, c.size);
  out += '}';
}

void MetroService::ClusterWriter::append_representative(std::string& out, std::uint32_t poi) const {
  const auto& rep = pois[leaf_poi ? (*leaf_poi)[poi] : poi];
  out += "{\"category\":";
  append_string(out, rep.category);
  out += ",\"id\":";
  append_string(out, rep.id);
  append_optional_field(out, "image", rep.image_url);
  out += ",\"name\":";
  append_string(out, rep.name);
  out += ",\"position\":";
  // Leaves are the POIs in input order, so the representative's leaf holds its position in
  // the tree's space (its warped position for space=layout).
  if (centers)
    append_lonlat(out, rep.pos);
  else
    append_xy(out, tree.nodes[poi].center);
  append_optional_field(out, "url", rep.url);
  append_optional_field(out, "wikipedia", rep.wikipedia);
  out += '}';
}

namespace {

// Approximate heap bytes of the cached values (vectors by capacity), for the cache budgets.
template <class T>
std::size_t bytes_of(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

std::size_t bytes_of(const CityMetroData& d) {
  return sizeof(d) + bytes_of(d.graph.pos) + bytes_of(d.graph.edges) + bytes_of(d.poi_xy) + bytes_of(d.poi_station_km);
}

std::size_t bytes_of(const CityLayout& l) {
  return sizeof(l) + l.body.capacity() + bytes_of(l.poi_layout) + bytes_of(l.poi_worth) + l.poi_outside.size() / 8;
}

std::size_t bytes_of(const poi::ClusterTree& t) { return sizeof(t) + bytes_of(t.nodes) + bytes_of(t.children); }

}  // namespace

MetroService::MetroService(Catalog& catalog, MipSolver mip, MetroLimits limits, MipSolver improve_mip)
    : catalog_(catalog),
      mip_(std::move(mip)),
      improve_mip_(std::move(improve_mip)),
      limits_(limits),
      data_(limits.data_cache_bytes),
      layouts_(limits.layout_cache_bytes),
      trees_(limits.tree_cache_bytes),
      geo_worth_(limits.worth_cache_bytes),
      geo_centers_(limits.worth_cache_bytes),
      improver_(limits.improve_queue) {
  if (!mip_) mip_ = [](const metro::MipModel& m, double t, double gap) { return metro::solve_with_cbc(m, t, gap); };
  if (!improve_mip_) improve_mip_ = mip_;
}

// The improver's thread uses the caches and the event sink: it stops before they go.
MetroService::~MetroService() { improver_.stop(); }

MetroService::ImprovementStats MetroService::improvement_stats() const {
  return {improver_.stats(), scheduled_.load(), improved_.load(), not_improved_.load(), stale_.load()};
}

std::shared_ptr<const CityMetroData> MetroService::data_for(const std::string& city_id) {
  require_slug(city_id, "city");
  auto city = catalog_.city(city_id);
  if (!city) throw not_found("id", "city", city_id);
  auto key = city->info.id + "@" + std::to_string(city->info.version);
  if (auto hit = data_.get(key)) return *hit;
  auto d = make_city_metro_data(city);
  data_.put(key, d, bytes_of(*d));
  return d;
}

std::shared_ptr<const CityLayout> MetroService::layout_for(const CityMetroData& data, const LayoutRequest& given,
                                                          bool* cached) {
  LayoutRequest req = given;  // the key needs the interests' canonical form (callers may not have it)
  resolve_interests(req, data);
  if (data.graph.edges.size() > limits_.max_layout_edges)
    throw ApiError(413, "too_large",
                   "id: the network has " + std::to_string(data.graph.edges.size()) +
                       " edges; layouts are made for at most " + std::to_string(limits_.max_layout_edges),
                   "id");
  const auto key = layout_key(data, req);
  *cached = true;
  if (auto hit = layouts_.get(key)) return *hit;
  bool ran = false;
  auto layout = layout_flight_.run(
      key,
      [&]() -> std::shared_ptr<const CityLayout> {
        auto db = catalog_.pool().acquire();
        if (auto stored = store::cache_get(*db, key)) return layout_from_body(std::move(stored->body));
        auto computed = compute_layout(data, req);
        store::cache_put(*db, key, "layout", {"application/json", computed->body});
        *cached = false;
        return computed;
      },
      &ran);
  layouts_.put(key, layout, bytes_of(*layout));
  return layout;
}

std::shared_ptr<const poi::ClusterTree> MetroService::tree_for(const std::string& key,
                                                              const std::vector<geo::XY>& points,
                                                              const std::vector<double>& worth,
                                                              const std::vector<bool>* skip) {
  if (auto hit = trees_.get(key)) return *hit;
  auto tree = tree_flight_.run(key, [&]() -> std::shared_ptr<const poi::ClusterTree> {
    auto db = catalog_.pool().acquire();
    if (auto stored = store::cache_get(*db, key)) {
      try {
        return std::make_shared<const poi::ClusterTree>(poi::deserialize(stored->body));
      } catch (const std::invalid_argument&) {  // an older or damaged entry: rebuild it
      }
    }
    std::vector<poi::ClusterPoint> in;
    for (std::size_t i = 0; i < points.size(); ++i)
      in.push_back({points[i], skip && (*skip)[i] ? 0.0 : worth[i]});
    std::shared_ptr<const poi::ClusterTree> made;
    // After a POI write: update the tree served for the previous version (api/cluster_tree_reuse).
    if (auto previous = latest_trees_.previous(key)) {
      poi::ClusterUpdateStats stats;
      if (auto derived = derive_tree(*previous, in, &stats)) {
        made = std::make_shared<const poi::ClusterTree>(std::move(*derived));
        ++(stats.rebuilt ? trees_built_ : trees_updated_);
      }
    }
    if (!made) {
      made = std::make_shared<const poi::ClusterTree>(poi::build_cluster_tree(in));
      ++trees_built_;
    }
    store::cache_put(*db, key, "clusters", {"application/octet-stream", poi::serialize(*made)});
    return made;
  });
  trees_.put(key, tree, bytes_of(*tree));
  latest_trees_.remember(key, tree);
  return tree;
}

// Every default layout is improved in the background (the MIP up to kAutoMipStations
// stations, room for names on any), unless improvements are off.
bool MetroService::improvable(const CityMetroData&) const { return limits_.improve_mip_s > 0; }

// What is computed for a request. A default (solver=auto) one is the fast layout alone: the
// MIP would keep the request waiting for up to a second or more, so it runs afterwards in the
// background (automatic_answer). Every other answer says that no improvement follows.
std::shared_ptr<const CityLayout> MetroService::compute_layout(const CityMetroData& data, const LayoutRequest& req) {
  if (req.solver == LayoutRequest::Solver::automatic) {
    LayoutRequest fast = req;
    fast.solver = LayoutRequest::Solver::fast;
    auto computed = compute_city_layout(data, fast, mip_);
    // Layouts for interests are not improved: a client moving sliders would queue a 10 s MIP
    // per step and push the default layouts' improvements out of the queue.
    if (improvable(data) && req.interests.empty()) return computed;  // undecided until served
    return with_body(*computed, with_improvement(computed->body, "none"));
  }
  auto computed = compute_city_layout(data, req, mip_);
  return with_body(*computed, with_improvement(computed->body, "none"));
}

// A default layout's answer: as cached once decided (improved, or nothing follows);
// otherwise its improvement is scheduled (deduplicated by key) and the answer says whether it
// was. The cached body stays undecided until the improvement has run, so a dropped or
// refused one is scheduled again by a later request.
std::string MetroService::automatic_answer(const std::shared_ptr<const CityMetroData>& data, const LayoutRequest& req,
                                           const CityLayout& layout) {
  if (!improvement_of(layout.body).empty()) return layout.body;
  const auto admission = improver_.push(layout_key(*data, req),
                                        [this, data, req](const std::atomic<bool>& stop) { improve(data, req, stop); });
  if (admission == LayoutImprover::Admission::queued) ++scheduled_;
  return with_improvement(layout.body, admission == LayoutImprover::Admission::refused ? "none" : "scheduled");
}

// True while the data is the city's current version: an improvement of an older one is
// dropped (its key is no longer asked for).
bool MetroService::current_version(const CityMetroData& data) {
  auto db = catalog_.pool().acquire();
  const auto version = store::city_version(*db, data.city->info.id);
  return version && *version == data.city->info.version;
}

// A background job (on the improver's thread): the default layout for `req` computed again
// with the same parameters, polished by the MIP (networks up to kAutoMipStations stations, CBC
// limited to MetroLimits::improve_mip_s) and given room for the names left out where symbols
// are 12 px across (metro/city_layout.hpp). When either wins (solver.kind "mip": fewer bends
// and no worse otherwise, metro/mip_polish.hpp; or solver.label_room.kept: more stations
// named, the layout's guarantees kept) it replaces the cached layout and is announced;
// otherwise the cached fast layout is marked as final.
void MetroService::improve(const std::shared_ptr<const CityMetroData>& data, const LayoutRequest& req,
                           const std::atomic<bool>& stop) {
  const auto key = layout_key(*data, req);
  if (auto hit = layouts_.get(key); hit && !improvement_of((*hit)->body).empty()) return;  // decided meanwhile
  if (!current_version(*data)) {
    ++stale_;
    return;
  }
  // Bounded: the fast path by the request's own time limit, the MIP by improve_mip_s plus
  // the solver's grace (MetroLimits); the deadline is a backstop on top of those. `stop` is
  // set at shutdown: the fast path's loops throw util::Stopped, the CBC child is killed.
  util::StopToken token;
  token.cancelled = &stop;
  token.deadline = util::StopToken::Clock::now() +
                   std::chrono::duration_cast<util::StopToken::Clock::duration>(
                       std::chrono::duration<double>(req.time_limit_s + limits_.improve_mip_s + 30.0));
  util::StopScope scope(token);
  LayoutRequest polish = req;
  polish.solver = data->city->info.station_count <= kAutoMipStations ? LayoutRequest::Solver::mip
                                                                     : LayoutRequest::Solver::fast;
  polish.label_room = true;
  // CBC gets improve_mip_s whatever the request's time limit (which bounds what its client
  // waits for: nobody waits for this job); the layout still skips the MIP when the request's
  // limit leaves it less than 0.2 s (metro/city_layout.cpp).
  const double budget = limits_.improve_mip_s;
  const MipSolver with_budget = [this, budget](const metro::MipModel& model, double, double gap) {
    return improve_mip_(model, budget, gap);
  };
  const auto result = compute_city_layout(*data, polish, with_budget);
  const auto doc = nlohmann::json::parse(result->body);
  util::check_stop();
  if (!current_version(*data)) {  // re-imported while the MIP ran
    ++stale_;
    return;
  }
  const auto& solver = doc.at("solver");
  const bool mip_won = solver.value("kind", "") == "mip";
  const bool names_won = solver.contains("label_room") && solver["label_room"].value("kept", 0) > 0;
  if (!mip_won && !names_won) {
    ++not_improved_;
    // What the job tried and why it kept nothing, for the client to say.
    nlohmann::json tried = nlohmann::json::object();
    for (const char* part : {"mip", "label_room"})
      if (solver.contains(part)) tried[part] = solver[part];
    mark_not_improved(key, tried.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    return;
  }
  replace_layout(key, with_body(*result, with_improvement(result->body, "applied")));
  ++improved_;
  if (!event_sink_) return;
  auto params = doc.at("params");
  params["solver"] = "auto";
  nlohmann::json event_solver = {{"kind", solver.at("kind")}, {"status", solver.at("status")}, {"gap", solver.at("gap")}};
  if (solver.contains("label_room")) event_solver["label_room"] = solver["label_room"];
  const nlohmann::json event = {{"type", "layout_improved"},
                                {"city", data->city->info.id},
                                {"version", data->city->info.version},
                                {"key", req.canonical()},
                                {"params", std::move(params)},
                                {"solver", event_solver},
                                {"quality", doc.at("quality")}};
  event_sink_(event.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

// The improvement did not win: the cached fast layout (in memory, else in the store) says that
// nothing follows, so it is not scheduled again, and what was tried (solver.tried: the job's
// `mip` and `label_room` reports, compact JSON in `tried`).
void MetroService::mark_not_improved(const std::string& key, const std::string& tried) {
  std::shared_ptr<const CityLayout> current;
  if (auto hit = layouts_.get(key)) {
    current = *hit;
  } else {
    auto db = catalog_.pool().acquire();
    if (auto stored = store::cache_get(*db, key)) current = layout_from_body(std::move(stored->body));
  }
  if (!current || !improvement_of(current->body).empty()) return;
  // Spliced in after `"solver":{` as the improvement field is (see with_improvement): the
  // body stays as it was but for these two members.
  auto body = current->body;
  if (const auto at = solver_members(body); at != std::string::npos && !tried.empty())
    body.insert(at, "\"tried\":" + tried + (body[at] == '}' ? "" : ","));
  replace_layout(key, with_body(*current, with_improvement(body, "none")));
}

void MetroService::replace_layout(const std::string& key, const std::shared_ptr<const CityLayout>& layout) {
  {
    auto db = catalog_.pool().acquire();
    store::cache_put(*db, key, "layout", {"application/json", layout->body});
  }
  layouts_.put(key, layout, bytes_of(*layout));
}

Response MetroService::layout(const Request& req, bool post) {
  auto params = post ? parse_layout_body(parse_json_body(req)) : parse_layout_query(req);
  auto data = data_for(req.param("id"));
  if (data->graph.edges.empty()) throw ApiError(422, "empty_network", "id: the city has no metro edges to lay out", "id");
  resolve_interests(params, *data);
  bool cached = false;
  auto layout = layout_for(*data, params, &cached);
  Response r;
  r.body = params.solver == LayoutRequest::Solver::automatic ? automatic_answer(data, params, *layout) : layout->body;
  r.cacheable = !post;
  r.headers.emplace_back("X-Result-Cache", cached ? "hit" : "miss");
  return r;
}

Response MetroService::visual_worth(const Request& req) {
  auto bbox = query_bbox(req);
  auto width = static_cast<std::size_t>(query_int(req, "width", 1, static_cast<long long>(limits_.max_raster_side), 128));
  auto height = static_cast<std::size_t>(query_int(req, "height", 1, static_cast<long long>(limits_.max_raster_side), 128));
  LayoutRequest params = parse_layout_query(req);  // rank, w_r, w_rho, k, interests
  auto data = data_for(req.param("id"));
  auto started = Clock::now();
  check_rank_source(*data, params.rank);
  auto vw = metro::make_visual_worth(*data, data->city->pois, params.rank, params.worth, interest_weights(params, *data));
  geo::BBox box = bbox ? *bbox : data->city->info.bbox;
  // The raster's cell centres, rows from north to south (image order), projected; then the
  // stations: one batched evaluation (exact within the work budget, else the bounded
  // approximation; see metro/visual_worth.hpp).
  const std::size_t cells = width * height;
  const auto& nodes = data->city->metro.nodes;
  std::vector<geo::XY> points;
  points.reserve(cells + nodes.size());
  for (std::size_t j = 0; j < height; ++j) {
    util::check_stop();
    for (std::size_t i = 0; i < width; ++i)
      points.push_back(geo::project(data->projection, {box.min_lon + (box.max_lon - box.min_lon) * (i + 0.5) / width,
                                                       box.max_lat - (box.max_lat - box.min_lat) * (j + 0.5) / height}));
  }
  for (std::size_t v = 0; v < nodes.size(); ++v)
    if (nodes[v].is_station()) points.push_back(data->graph.pos[v]);
  const auto worth = vw.at_points(points);
  double max = 0;
  for (std::size_t k = 0; k < cells; ++k) max = std::max(max, worth[k]);
  nlohmann::json values = nlohmann::json::array();
  for (std::size_t k = 0; k < cells; ++k) values.push_back(max > 0 ? std::round(worth[k] / max * 1000) / 1000 : 0.0);
  nlohmann::json stations = nlohmann::json::array();
  for (std::size_t v = 0, s = cells; v < nodes.size(); ++v)
    if (nodes[v].is_station()) stations.push_back({{"id", nodes[v].id}, {"worth", max > 0 ? worth[s++] / max : 0.0}});
  Response r = json_response({{"city", data->city->info.id},
                              {"bbox", bbox_json(box)},
                              {"width", width},
                              {"height", height},
                              {"values", std::move(values)},
                              {"max", max},
                              {"pois", vw.size()},
                              {"stations", std::move(stations)}});
  r.cacheable = true;
  set_server_timing(r, started);
  return r;
}

namespace {

// A cluster tree's input with interests (weights per POI, interest_weights): each POI's worth
// times its own weight, so that the prominence and the representatives follow the interests
// too; the POIs of weight 0 are left out (they are not shown), `leaf_poi` maps the leaves
// back to the POIs.
struct WeightedClusterInput {
  std::vector<geo::XY> points;
  std::vector<double> worth;
  std::vector<bool> skip;
  std::shared_ptr<std::vector<std::uint32_t>> leaf_poi = std::make_shared<std::vector<std::uint32_t>>();
};

WeightedClusterInput weighted_cluster_input(const std::vector<geo::XY>& points, const std::vector<double>& worth,
                                            const std::vector<bool>* skip, const std::vector<double>& weight) {
  WeightedClusterInput in;
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    if (weight[i] <= 0) continue;
    in.points.push_back(points[i]);
    in.worth.push_back(worth[i] * weight[i]);
    in.skip.push_back(skip && (*skip)[i]);
    in.leaf_poi->push_back(i);
  }
  return in;
}

}  // namespace

MetroService::ClusterWindow MetroService::geo_window(const Request& req, const CityMetroData& data,
                                                     const std::string* bbox_text) {
  // Only the part of the window where the city has POIs matters, and it must be cut to that
  // before projecting: the city's local transverse Mercator is meaningless far from the city
  // (a whole-world window used to project to a box holding nothing, so 0 clusters).
  const auto& pois = data.city->info.poi_bbox;
  auto box = bbox_text ? parse_bbox(*bbox_text, "bbox") : pois;
  box = {std::max(box.min_lon, pois.min_lon), std::max(box.min_lat, pois.min_lat), std::min(box.max_lon, pois.max_lon),
         std::min(box.max_lat, pois.max_lat)};
  ClusterWindow w;
  if (box.empty()) {  // no POI can be inside (or the city has none)
    w.empty = true;
    box = pois.empty() ? geo::BBox{data.city->info.bbox} : pois;  // something finite to project
  }
  // The window in metres: the projected box's corners' extent.
  const geo::XY corners[] = {geo::project(data.projection, {box.min_lon, box.min_lat}),
                             geo::project(data.projection, {box.max_lon, box.max_lat}),
                             geo::project(data.projection, {box.min_lon, box.max_lat}),
                             geo::project(data.projection, {box.max_lon, box.min_lat})};
  w.lo = w.hi = corners[0];
  for (const auto& c : corners) {
    w.lo = {std::min(w.lo.x, c.x), std::min(w.lo.y, c.y)};
    w.hi = {std::max(w.hi.x, c.x), std::max(w.hi.y, c.y)};
  }
  // Interests (only they of the layout parameters matter here): "" without.
  auto interests = parse_layout_query(req);
  resolve_interests(interests, data);
  const auto weights = poi::poi_interest_weights(interests.interests, data.categories);
  const auto suffix = interests_key(interests);
  auto worth_key = "worth:" + data.key + suffix;
  std::shared_ptr<const std::vector<double>> worth;
  if (auto hit = geo_worth_.get(worth_key)) {
    worth = *hit;
  } else {
    worth = std::make_shared<const std::vector<double>>(poi_worth_geo(data, RankSource::automatic, {}, weights));
    geo_worth_.put(worth_key, worth, bytes_of(*worth));
  }
  const auto tree_key = "clusters:geo:" + data.key + suffix;
  if (weights.empty()) {
    w.tree = tree_for(tree_key, data.poi_xy, *worth, nullptr);
  } else {
    auto in = weighted_cluster_input(data.poi_xy, *worth, nullptr, weights);
    w.tree = tree_for(tree_key, in.points, in.worth, nullptr);
    w.leaf_poi = std::move(in.leaf_poi);
  }
  w.centers = geo_centers(tree_key, w.tree, data.projection);
  return w;
}

// The geographic tree's node centres in lon/lat, unprojected once per tree (per city version)
// rather than for every cluster of every answer (the inverse transverse Mercator was ~3 % of
// a cluster request).
std::shared_ptr<const MetroService::GeoCenters> MetroService::geo_centers(
    const std::string& tree_key, const std::shared_ptr<const poi::ClusterTree>& tree,
    const geo::LocalProjection& projection) {
  if (auto hit = geo_centers_.get(tree_key); hit && (*hit)->tree.lock() == tree) return *hit;
  auto made = std::make_shared<GeoCenters>();
  made->tree = tree;
  made->centers.reserve(tree->nodes.size());
  for (const auto& node : tree->nodes) made->centers.push_back(geo::unproject(projection, node.center));
  geo_centers_.put(tree_key, made, bytes_of(made->centers));
  return made;
}

MetroService::ClusterWindow MetroService::layout_window(const Request& req, const CityMetroData& data,
                                                        const std::string* bbox_text) {
  // Layout space: the bbox is in the layout's frame (metres, see GET .../layout).
  if (!bbox_text) throw bad("bbox", "required for space=layout (x0,y0,x1,y1 in the layout frame)");
  ClusterWindow w;
  parse_layout_bbox(*bbox_text, w.lo, w.hi);
  auto params = parse_layout_query(req);
  resolve_interests(params, data);
  bool cached = false;
  auto layout = layout_for(data, params, &cached);
  // The key holds the interests (canonical()): the layout and the cluster worth follow them.
  auto tree_key = "clusters:layout:" + data.key + ":" + params.canonical();
  // An improved layout moved the POIs: its tree is another one (a key of its own, so that a
  // tree built from the fast layout, in memory or in the store, is never taken for it).
  if (improvement_of(layout->body) == "applied") tree_key += ":improved";
  const auto weights = poi::poi_interest_weights(params.interests, data.categories);
  if (weights.empty()) {
    w.tree = tree_for(tree_key, layout->poi_layout, layout->poi_worth, &layout->poi_outside);
  } else {
    auto in = weighted_cluster_input(layout->poi_layout, layout->poi_worth, &layout->poi_outside, weights);
    w.tree = tree_for(tree_key, in.points, in.worth, &in.skip);
    w.leaf_poi = std::move(in.leaf_poi);
  }
  return w;
}

Response MetroService::clusters(const Request& req) {
  auto started = Clock::now();
  const std::string* space_param = req.query_param("space");
  const std::string space = space_param ? *space_param : "geo";
  if (space != "geo" && space != "layout") throw bad("space", "expected geo or layout");
  auto m = static_cast<std::size_t>(query_int(req, "m", 1, static_cast<long long>(limits_.max_m), 10));
  auto data = data_for(req.param("id"));
  const auto* bbox_text = req.query_param("bbox");
  const bool geo_space = space == "geo";
  const ClusterWindow w = geo_space ? geo_window(req, *data, bbox_text) : layout_window(req, *data, bbox_text);

  // At least 2M active clusters where the tree allows, so a whole-map window fills the top M
  // and the M previews (see poi/active_clusters.hpp).
  const auto active = w.empty ? poi::ActiveClusters{} : poi::active_clusters(*w.tree, w.lo, w.hi, m, 2 * m);
  const ClusterWriter writer{*w.tree, data->city->pois, w.centers ? &w.centers->centers : nullptr, w.leaf_poi.get()};
  // Keys in alphabetical order, as nlohmann::json (std::map) wrote them before.
  Response r;
  std::string& out = r.body;
  out.reserve(256 + 480 * (active.top.size() + active.previews.size()));
  out += "{\"active\":";
  append_integer(out, static_cast<std::int64_t>(active.active));
  out += ",\"city\":";
  append_string(out, data->city->info.id);
  out += ",\"clusters\":";
  writer.append_list(out, active.top, active.prominence.data());
  out += ",\"previews\":";
  writer.append_list(out, active.previews, active.prominence.data() + active.top.size());
  out += ",\"space\":";
  append_string(out, space);
  out += '}';
  r.cacheable = true;
  set_server_timing(r, started);
  return r;
}

}  // namespace tourmap::api
