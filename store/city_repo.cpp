#include "import_log.hpp"
#include "repo.hpp"

#include <nlohmann/json.hpp>

#include <cstring>

namespace tourmap::store {
namespace {

std::vector<unsigned char> pack_polyline(const std::vector<geo::LonLat>& pts) {
  std::vector<unsigned char> out(pts.size() * 2 * sizeof(double));
  auto* p = out.data();
  for (const auto& pt : pts) {
    std::memcpy(p, &pt.lon, sizeof(double));
    std::memcpy(p + sizeof(double), &pt.lat, sizeof(double));
    p += 2 * sizeof(double);
  }
  return out;
}

std::vector<geo::LonLat> unpack_polyline(const std::vector<unsigned char>& blob) {
  std::vector<geo::LonLat> pts(blob.size() / (2 * sizeof(double)));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    std::memcpy(&pts[i].lon, blob.data() + i * 2 * sizeof(double), sizeof(double));
    std::memcpy(&pts[i].lat, blob.data() + i * 2 * sizeof(double) + sizeof(double), sizeof(double));
  }
  return pts;
}

// metro_lines.style: '' for a plain stroke, else {"casing": true, "dash": [2, 1]} (either part).
std::string style_text(const model::LineStyle& style) {
  if (style.plain()) return "";
  nlohmann::json j = nlohmann::json::object();
  if (style.casing) j["casing"] = true;
  if (!style.dash.empty()) j["dash"] = style.dash;
  return j.dump();
}

model::LineStyle parse_style(const std::string& text) {
  model::LineStyle style;
  if (text.empty()) return style;
  auto j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object()) return style;  // written by style_text only; a damaged value draws plain
  if (j.contains("casing") && j["casing"].is_boolean()) style.casing = j["casing"].get<bool>();
  if (j.contains("dash") && j["dash"].is_array())
    for (const auto& d : j["dash"])
      if (d.is_number()) style.dash.push_back(d.get<double>());
  return style;
}

constexpr const char* kCitySelect =
    "SELECT c.id, c.name, c.min_lon, c.min_lat, c.max_lon, c.max_lat, c.proj_lon0, c.proj_lat0,"
    " c.attribution, c.poi_attribution, c.version,"
    " (SELECT COUNT(*) FROM metro_nodes n WHERE n.city_id = c.id AND n.station_id IS NOT NULL),"
    " (SELECT COUNT(*) FROM metro_edges e WHERE e.city_id = c.id),"
    " (SELECT COUNT(*) FROM metro_lines l WHERE l.city_id = c.id),"
    " (SELECT COUNT(*) FROM pois p WHERE p.city_id = c.id),"
    " (SELECT MIN(lon) FROM pois p WHERE p.city_id = c.id), (SELECT MIN(lat) FROM pois p WHERE p.city_id = c.id),"
    " (SELECT MAX(lon) FROM pois p WHERE p.city_id = c.id), (SELECT MAX(lat) FROM pois p WHERE p.city_id = c.id)"
    " FROM cities c";

model::CityInfo read_city_info(const Stmt& st) {
  model::CityInfo info;
  info.id = st.text(0);
  info.name = st.text(1);
  info.bbox = {st.real(2), st.real(3), st.real(4), st.real(5)};
  info.projection.origin = {st.real(6), st.real(7)};
  info.attribution = st.text(8);
  info.poi_attribution = st.text(9);
  info.version = st.int64(10);
  info.station_count = static_cast<std::size_t>(st.int64(11));
  info.edge_count = static_cast<std::size_t>(st.int64(12));
  info.line_count = static_cast<std::size_t>(st.int64(13));
  info.poi_count = static_cast<std::size_t>(st.int64(14));
  if (info.poi_count > 0) info.poi_bbox = {st.real(15), st.real(16), st.real(17), st.real(18)};
  return info;
}

}  // namespace

std::int64_t save_city_metro(Db& db, const CityMeta& meta, const model::MetroNetwork& net, ImportRecord record) {
  Transaction tx(db);
  record.kind = "metro";
  record.target_id = meta.id;
  auto version = record_import(db, record);
  auto box = model::bbox_of(net);
  auto proj = geo::projection_for(box);

  db.prepare(
        "INSERT INTO cities (id, name, min_lon, min_lat, max_lon, max_lat, proj_lon0, proj_lat0, projection,"
        " attribution, version) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)"
        " ON CONFLICT (id) DO UPDATE SET name = excluded.name, min_lon = excluded.min_lon,"
        " min_lat = excluded.min_lat, max_lon = excluded.max_lon, max_lat = excluded.max_lat,"
        " proj_lon0 = excluded.proj_lon0, proj_lat0 = excluded.proj_lat0, projection = excluded.projection,"
        " attribution = excluded.attribution, version = excluded.version")
      .bind(1, meta.id).bind(2, meta.name)
      .bind(3, box.min_lon).bind(4, box.min_lat).bind(5, box.max_lon).bind(6, box.max_lat)
      .bind(7, proj.origin.lon).bind(8, proj.origin.lat).bind(9, geo::describe(proj))
      .bind(10, meta.attribution).bind(11, version)
      .run();
  for (const char* table : {"metro_edges", "metro_nodes", "metro_lines"})
    db.prepare(std::string("DELETE FROM ") + table + " WHERE city_id = ?").bind(1, meta.id).run();

  auto ins_line =
      db.prepare("INSERT INTO metro_lines (city_id, idx, id, label, color, style) VALUES (?, ?, ?, ?, ?, ?)");
  for (std::size_t i = 0; i < net.lines.size(); ++i) {
    const auto& l = net.lines[i];
    ins_line.bind(1, meta.id).bind(2, i).bind(3, l.id).bind(4, l.label).bind(5, l.color).bind(6, style_text(l.style)).run();
  }
  auto ins_node = db.prepare(
      "INSERT INTO metro_nodes (city_id, idx, id, station_id, name, lon, lat) VALUES (?, ?, ?, ?, ?, ?, ?)");
  for (std::size_t i = 0; i < net.nodes.size(); ++i) {
    const auto& n = net.nodes[i];
    ins_node.bind(1, meta.id).bind(2, i).bind(3, n.id);
    if (n.is_station()) ins_node.bind(4, n.station_id); else ins_node.bind_null(4);
    ins_node.bind(5, n.name).bind(6, n.pos.lon).bind(7, n.pos.lat).run();
  }
  auto ins_edge = db.prepare(
      "INSERT INTO metro_edges (city_id, idx, from_idx, to_idx, line_idxs, geometry) VALUES (?, ?, ?, ?, ?, ?)");
  for (std::size_t i = 0; i < net.edges.size(); ++i) {
    const auto& e = net.edges[i];
    auto blob = pack_polyline(e.geometry);
    ins_edge.bind(1, meta.id).bind(2, i).bind(3, static_cast<std::int64_t>(e.from))
        .bind(4, static_cast<std::int64_t>(e.to)).bind(5, nlohmann::json(e.lines).dump())
        .bind_blob(6, blob.data(), blob.size()).run();
  }
  tx.commit();
  return version;
}

std::int64_t save_city_pois(Db& db, const std::string& city_id, const std::string& attribution,
                            const std::vector<model::Poi>& pois, ImportRecord record) {
  Transaction tx(db);
  if (!city_version(db, city_id))
    throw DbError("unknown city '" + city_id + "': import its metro network first");
  record.kind = "pois";
  record.target_id = city_id;
  auto version = record_import(db, record);
  db.prepare("UPDATE cities SET version = ?, poi_attribution = ? WHERE id = ?")
      .bind(1, version).bind(2, attribution).bind(3, city_id).run();
  db.prepare("DELETE FROM pois WHERE city_id = ?").bind(1, city_id).run();
  auto ins = db.prepare(
      "INSERT INTO pois (city_id, idx, id, name, lon, lat, category, image_url, url, wikipedia, rank, popularity)"
      " VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (std::size_t i = 0; i < pois.size(); ++i) {
    const auto& p = pois[i];
    ins.bind(1, city_id).bind(2, i).bind(3, p.id).bind(4, p.name).bind(5, p.pos.lon).bind(6, p.pos.lat)
        .bind(7, p.category).bind(8, p.image_url).bind(9, p.url).bind(10, p.wikipedia).bind(11, p.rank)
        .bind(12, p.popularity).run();
  }
  tx.commit();
  return version;
}

std::vector<model::CityInfo> list_cities(Db& db) {
  auto st = db.prepare(std::string(kCitySelect) + " ORDER BY c.name");
  std::vector<model::CityInfo> out;
  while (st.step()) out.push_back(read_city_info(st));
  return out;
}

std::optional<model::CityInfo> find_city(Db& db, const std::string& id) {
  auto st = db.prepare(std::string(kCitySelect) + " WHERE c.id = ?");
  st.bind(1, id);
  if (!st.step()) return std::nullopt;
  return read_city_info(st);
}

std::optional<std::int64_t> city_version(Db& db, const std::string& id) {
  auto st = db.cached("SELECT version FROM cities WHERE id = ?");  // on every city request
  st->bind(1, id);
  if (!st->step()) return std::nullopt;
  return st->int64(0);
}

std::optional<model::City> load_city(Db& db, const std::string& id) {
  // One read transaction so the city is consistent even while an import commits.
  ReadTransaction read(db);

  auto info = find_city(db, id);
  if (!info) return std::nullopt;
  model::City city;
  city.info = *info;

  auto lines = db.prepare("SELECT id, label, color, style FROM metro_lines WHERE city_id = ? ORDER BY idx");
  lines.bind(1, id);
  while (lines.step())
    city.metro.lines.push_back({lines.text(0), lines.text(1), lines.text(2), parse_style(lines.text(3))});

  auto nodes = db.prepare("SELECT id, station_id, name, lon, lat FROM metro_nodes WHERE city_id = ? ORDER BY idx");
  nodes.bind(1, id);
  while (nodes.step())
    city.metro.nodes.push_back({nodes.text(0), nodes.text(1), nodes.text(2), {nodes.real(3), nodes.real(4)}});

  auto edges = db.prepare("SELECT from_idx, to_idx, line_idxs, geometry FROM metro_edges WHERE city_id = ? ORDER BY idx");
  edges.bind(1, id);
  while (edges.step()) {
    model::MetroEdge e;
    e.from = static_cast<std::uint32_t>(edges.int64(0));
    e.to = static_cast<std::uint32_t>(edges.int64(1));
    e.lines = nlohmann::json::parse(edges.text(2)).get<std::vector<std::uint32_t>>();
    e.geometry = unpack_polyline(edges.blob(3));
    city.metro.edges.push_back(std::move(e));
  }

  auto pois = db.prepare(
      "SELECT id, name, lon, lat, category, image_url, url, wikipedia, rank, popularity FROM pois"
      " WHERE city_id = ? ORDER BY idx");
  pois.bind(1, id);
  while (pois.step()) {
    model::Poi p;
    p.id = pois.text(0);
    p.name = pois.text(1);
    p.pos = {pois.real(2), pois.real(3)};
    p.category = pois.text(4);
    p.image_url = pois.text(5);
    p.url = pois.text(6);
    p.wikipedia = pois.text(7);
    p.rank = pois.opt_real(8);
    p.popularity = pois.opt_real(9);
    city.pois.push_back(std::move(p));
  }
  return city;
}

bool delete_city(Db& db, const std::string& id) {
  Transaction tx(db);
  auto st = db.prepare("DELETE FROM cities WHERE id = ?");
  st.bind(1, id).run();
  bool deleted = db.changes() > 0;
  if (deleted) record_deletion(db, "city", id);  // so the same files import again
  tx.commit();
  return deleted;
}

}  // namespace tourmap::store
