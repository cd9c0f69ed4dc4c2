// The context layers of a road network (migrations/0005_road_context.sql): one row per
// feature, its geometry packed little-endian in a blob (the layout is in the migration).
#include "repo.hpp"

#include <bit>
#include <cstring>

namespace tourmap::store {
namespace {

void put_u32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}
void put_f64(std::vector<unsigned char>& out, double d) {
  const auto v = std::bit_cast<std::uint64_t>(d);
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}
void put_ring(std::vector<unsigned char>& out, const std::vector<geo::LonLat>& ring) {
  put_u32(out, static_cast<std::uint32_t>(ring.size()));
  for (const auto& p : ring) {
    put_f64(out, p.lon);
    put_f64(out, p.lat);
  }
}

// Reads a blob written above; a short or inconsistent one is a DbError (never read past it).
struct BlobReader {
  const std::vector<unsigned char>& data;
  const std::string& network;
  std::size_t at = 0;
  void need(std::size_t n) {
    if (data.size() - at < n) throw DbError("road network '" + network + "': a context geometry is truncated");
  }
  std::uint32_t u32() {
    need(4);
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(data[at + static_cast<std::size_t>(i)]) << (8 * i);
    at += 4;
    return v;
  }
  double f64() {
    need(8);
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(data[at + static_cast<std::size_t>(i)]) << (8 * i);
    at += 8;
    return std::bit_cast<double>(v);
  }
  std::vector<geo::LonLat> ring() {
    const std::uint32_t n = u32();
    need(static_cast<std::size_t>(n) * 16);
    std::vector<geo::LonLat> out(n);
    for (auto& p : out) {
      p.lon = f64();
      p.lat = f64();
    }
    return out;
  }
};

}  // namespace

void save_road_context(Db& db, const std::string& network_id, const model::ContextLayers& layers) {
  db.prepare("DELETE FROM road_context WHERE network_id = ?").bind(1, network_id).run();
  auto ins = db.prepare(
      "INSERT INTO road_context (network_id, seq, layer, kind, name, rank, tunnel, geometry)"
      " VALUES (?, ?, ?, ?, ?, ?, ?, ?)");
  std::int64_t seq = 0;
  std::vector<unsigned char> blob;
  const auto insert = [&](const char* layer, std::string_view kind, const std::string& name, int rank, bool tunnel) {
    ins.bind(1, network_id).bind(2, seq++).bind(3, std::string(layer)).bind(4, std::string(kind)).bind(5, name)
        .bind(6, static_cast<std::int64_t>(rank)).bind(7, static_cast<std::int64_t>(tunnel ? 1 : 0))
        .bind_blob(8, blob.data(), blob.size())
        .run();
  };
  for (const auto& a : layers.areas) {
    blob.clear();
    put_u32(blob, static_cast<std::uint32_t>(a.rings.size()));
    for (const auto& r : a.rings) put_ring(blob, r);
    insert("area", model::name_of(a.kind), "", 0, false);
  }
  for (const auto& l : layers.lines) {
    blob.clear();
    put_ring(blob, l.points);
    insert("line", model::name_of(l.kind), l.name, 0, l.tunnel);
  }
  for (const auto& p : layers.places) {
    blob.clear();
    put_f64(blob, p.pos.lon);
    put_f64(blob, p.pos.lat);
    insert("place", model::name_of(p.kind), p.name, p.rank, false);
  }
}

model::ContextLayers load_road_context(Db& db, const std::string& network_id) {
  ReadTransaction read(db);
  model::ContextLayers out;
  auto st = db.prepare(
      "SELECT layer, kind, name, rank, tunnel, geometry FROM road_context WHERE network_id = ? ORDER BY seq");
  st.bind(1, network_id);
  while (st.step()) {
    const std::string layer = st.text(0), kind = st.text(1);
    const auto blob = st.blob(5);
    BlobReader in{blob, network_id};
    const auto bad_kind = [&] { return DbError("road network '" + network_id + "': unknown context kind '" + kind + "'"); };
    if (layer == "area") {
      model::ContextArea a;
      const auto k = model::area_kind_named(kind);
      if (!k) throw bad_kind();
      a.kind = *k;
      const std::uint32_t rings = in.u32();
      in.need(static_cast<std::size_t>(rings) * 4);
      for (std::uint32_t i = 0; i < rings; ++i) a.rings.push_back(in.ring());
      out.areas.push_back(std::move(a));
    } else if (layer == "line") {
      model::ContextLine l;
      const auto k = model::line_kind_named(kind);
      if (!k) throw bad_kind();
      l.kind = *k;
      l.name = st.text(2);
      l.tunnel = st.int64(4) != 0;
      l.points = in.ring();
      out.lines.push_back(std::move(l));
    } else {
      model::ContextPlace p;
      const auto k = model::place_kind_named(kind);
      if (!k) throw bad_kind();
      p.kind = *k;
      p.name = st.text(2);
      p.rank = static_cast<int>(st.int64(3));
      p.pos.lon = in.f64();
      p.pos.lat = in.f64();
      out.places.push_back(std::move(p));
    }
  }
  return out;
}

}  // namespace tourmap::store
