#include "import_log.hpp"
#include "repo.hpp"

namespace tourmap::store {
namespace {

constexpr const char* kRoadSelect =
    "SELECT id, name, min_lon, min_lat, max_lon, max_lat, proj_lon0, proj_lat0, attribution, version,"
    " node_count, way_count, edge_count FROM road_networks";

model::RoadNetworkInfo read_info(const Stmt& st) {
  model::RoadNetworkInfo info;
  info.id = st.text(0);
  info.name = st.text(1);
  info.bbox = {st.real(2), st.real(3), st.real(4), st.real(5)};
  info.projection.origin = {st.real(6), st.real(7)};
  info.attribution = st.text(8);
  info.version = st.int64(9);
  info.node_count = static_cast<std::size_t>(st.int64(10));
  info.way_count = static_cast<std::size_t>(st.int64(11));
  info.edge_count = static_cast<std::size_t>(st.int64(12));
  return info;
}

}  // namespace

std::int64_t save_road_network(Db& db, const RoadMeta& meta, const model::RoadNetwork& net, ImportRecord record,
                               const model::ContextLayers& context) {
  Transaction tx(db);
  record.kind = "roads";
  record.target_id = meta.id;
  auto version = record_import(db, record);
  auto box = model::bbox_of(net);
  auto proj = geo::projection_for(box);

  // Replacing a network: drop the old rows (cascade) and write the new ones.
  db.prepare("DELETE FROM road_networks WHERE id = ?").bind(1, meta.id).run();
  db.prepare(
        "INSERT INTO road_networks (id, name, min_lon, min_lat, max_lon, max_lat, proj_lon0, proj_lat0,"
        " projection, attribution, node_count, way_count, edge_count, version)"
        " VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)")
      .bind(1, meta.id).bind(2, meta.name)
      .bind(3, box.min_lon).bind(4, box.min_lat).bind(5, box.max_lon).bind(6, box.max_lat)
      .bind(7, proj.origin.lon).bind(8, proj.origin.lat).bind(9, geo::describe(proj))
      .bind(10, meta.attribution).bind(11, net.nodes.size()).bind(12, net.ways.size())
      .bind(13, net.edges.size()).bind(14, version)
      .run();

  auto ins_node = db.prepare("INSERT INTO road_nodes (network_id, idx, osm_id, lon, lat) VALUES (?, ?, ?, ?, ?)");
  for (std::size_t i = 0; i < net.nodes.size(); ++i) {
    const auto& n = net.nodes[i];
    ins_node.bind(1, meta.id).bind(2, i).bind(3, n.osm_id).bind(4, n.pos.lon).bind(5, n.pos.lat).run();
  }
  auto ins_way = db.prepare("INSERT INTO road_ways (network_id, idx, osm_id, highway, name) VALUES (?, ?, ?, ?, ?)");
  for (std::size_t i = 0; i < net.ways.size(); ++i) {
    const auto& w = net.ways[i];
    ins_way.bind(1, meta.id).bind(2, i).bind(3, w.osm_id).bind(4, w.highway).bind(5, w.name).run();
  }
  auto ins_edge = db.prepare(
      "INSERT INTO road_edges (network_id, idx, way_idx, from_idx, to_idx) VALUES (?, ?, ?, ?, ?)");
  for (std::size_t i = 0; i < net.edges.size(); ++i) {
    const auto& e = net.edges[i];
    ins_edge.bind(1, meta.id).bind(2, i).bind(3, static_cast<std::int64_t>(e.way))
        .bind(4, static_cast<std::int64_t>(e.from)).bind(5, static_cast<std::int64_t>(e.to)).run();
  }
  save_road_context(db, meta.id, context);
  tx.commit();
  return version;
}

std::vector<model::RoadNetworkInfo> list_road_networks(Db& db) {
  auto st = db.prepare(std::string(kRoadSelect) + " ORDER BY edge_count");
  std::vector<model::RoadNetworkInfo> out;
  while (st.step()) out.push_back(read_info(st));
  return out;
}

std::optional<model::RoadNetworkInfo> find_road_network(Db& db, const std::string& id) {
  auto st = db.cached(std::string(kRoadSelect) + " WHERE id = ?");  // on every road request
  st->bind(1, id);
  if (!st->step()) return std::nullopt;
  return read_info(*st);
}

std::optional<std::int64_t> road_network_version(Db& db, const std::string& id) {
  auto st = db.prepare("SELECT version FROM road_networks WHERE id = ?");
  st.bind(1, id);
  if (!st.step()) return std::nullopt;
  return st.int64(0);
}

std::optional<model::RoadNetwork> load_road_network(Db& db, const std::string& id) {
  ReadTransaction read(db);  // consistent snapshot while an import may commit
  if (!road_network_version(db, id)) return std::nullopt;

  model::RoadNetwork net;
  auto nodes = db.prepare("SELECT osm_id, lon, lat FROM road_nodes WHERE network_id = ? ORDER BY idx");
  nodes.bind(1, id);
  while (nodes.step()) net.nodes.push_back({nodes.int64(0), {nodes.real(1), nodes.real(2)}});

  auto ways = db.prepare("SELECT osm_id, highway, name FROM road_ways WHERE network_id = ? ORDER BY idx");
  ways.bind(1, id);
  while (ways.step()) net.ways.push_back({ways.int64(0), ways.text(1), ways.text(2), {}});

  auto edges = db.prepare("SELECT way_idx, from_idx, to_idx FROM road_edges WHERE network_id = ? ORDER BY idx");
  edges.bind(1, id);
  while (edges.step()) {
    model::RoadEdge e{static_cast<std::uint32_t>(edges.int64(1)), static_cast<std::uint32_t>(edges.int64(2)),
                      static_cast<std::uint32_t>(edges.int64(0))};
    if (e.way >= net.ways.size() || e.from >= net.nodes.size() || e.to >= net.nodes.size())
      throw DbError("road network '" + id + "' is inconsistent: edge refers to a missing way or node");
    // Rebuild each way's node sequence from its edges (they are stored in way order).
    auto& seq = net.ways[e.way].nodes;
    if (seq.empty()) seq.push_back(e.from);
    seq.push_back(e.to);
    net.edges.push_back(e);
  }
  return net;
}

bool delete_road_network(Db& db, const std::string& id) {
  Transaction tx(db);
  db.prepare("DELETE FROM road_networks WHERE id = ?").bind(1, id).run();
  bool deleted = db.changes() > 0;
  if (deleted) record_deletion(db, "roads", id);  // so the same file imports again
  tx.commit();
  return deleted;
}

}  // namespace tourmap::store
