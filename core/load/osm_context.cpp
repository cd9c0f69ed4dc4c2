#include "load/osm_context.hpp"

#include "load/coastline_sea.hpp"
#include "load/file.hpp"
#include "load/load_error.hpp"
#include "load/osm_input.hpp"
#include "util/stop.hpp"

// GCC 12 takes the user name libosmium's AreaBuilder copies from the object it builds from for
// a read past that object (the name follows it in the buffer): a false -Wstringop-overread that
// libosmium's maintainers switch off for GCC too (osmcode/libosmium#397).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-overread"
#endif
#include <osmium/area/assembler.hpp>
#include <osmium/area/multipolygon_manager.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#include <osmium/handler.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/flex_mem.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/osm/area.hpp>
#include <osmium/tags/tags_filter.hpp>
#include <osmium/visitor.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <optional>

namespace tourmap::load {
namespace {

using model::ContextAreaKind;
using model::ContextLineKind;
using model::ContextPlaceKind;
using LocationIndex = osmium::index::map::FlexMem<osmium::unsigned_object_id_type, osmium::Location>;
using LocationHandler = osmium::handler::NodeLocationsForWays<LocationIndex>;

bool is(const char* value, const char* expected) { return value && std::strcmp(value, expected) == 0; }

bool is_any(const char* value, std::initializer_list<const char*> expected) {
  return value &&
         std::any_of(expected.begin(), expected.end(), [&](const char* e) { return std::strcmp(value, e) == 0; });
}

// The area kind of a closed way's or a multipolygon's tags (the table in osm_context.hpp).
std::optional<ContextAreaKind> area_kind_of(const osmium::TagList& tags) {
  const char* natural = tag_value(tags, "natural");
  const char* landuse = tag_value(tags, "landuse");
  const char* leisure = tag_value(tags, "leisure");
  const char* building = tag_value(tags, "building");
  if (is(natural, "water") || is_any(tag_value(tags, "waterway"), {"riverbank", "dock"}) ||
      is_any(landuse, {"reservoir", "basin"}) || tag_value(tags, "water"))
    return ContextAreaKind::water;
  if (building && !is(building, "no")) return ContextAreaKind::building;
  if (is_any(leisure, {"park", "garden"})) return ContextAreaKind::park;
  if (is(landuse, "forest") || is(natural, "wood")) return ContextAreaKind::forest;
  if (is_any(landuse, {"grass", "village_green", "recreation_ground"}) || is(natural, "grassland") ||
      is(leisure, "pitch"))
    return ContextAreaKind::grass;
  if (is_any(landuse, {"farmland", "meadow", "orchard", "vineyard"})) return ContextAreaKind::farmland;
  if (is(landuse, "residential")) return ContextAreaKind::residential;
  if (is_any(landuse, {"industrial", "commercial", "retail"})) return ContextAreaKind::industrial;
  return std::nullopt;
}

// The keys area_kind_of looks at: the relations manager keeps only multipolygons with one of
// them (and their member ways) in memory, and offers only closed ways with one to assemble.
osmium::TagsFilter area_keys() {
  osmium::TagsFilter filter{false};
  for (const char* key : {"natural", "landuse", "leisure", "building", "water", "waterway"})
    filter.add_rule(true, osmium::TagMatcher{key});
  return filter;
}

std::optional<ContextLineKind> line_kind_of(const osmium::TagList& tags) {
  const char* waterway = tag_value(tags, "waterway");
  if (is(waterway, "river")) return ContextLineKind::river;
  if (is(waterway, "stream")) return ContextLineKind::stream;
  if (is(waterway, "canal")) return ContextLineKind::canal;
  if (is_any(tag_value(tags, "railway"), {"rail", "light_rail", "tram", "subway", "narrow_gauge"}) &&
      !is(tag_value(tags, "disused"), "yes") && !is(tag_value(tags, "abandoned"), "yes"))
    return ContextLineKind::railway;
  return std::nullopt;
}

std::optional<ContextPlaceKind> place_kind_of(const char* place) {
  if (!place) return std::nullopt;
  struct Entry {
    const char* value;
    ContextPlaceKind kind;
  };
  static constexpr Entry kPlaces[] = {
      {"city", ContextPlaceKind::city},         {"town", ContextPlaceKind::town},
      {"village", ContextPlaceKind::village},   {"suburb", ContextPlaceKind::suburb},
      {"quarter", ContextPlaceKind::suburb},    {"borough", ContextPlaceKind::suburb},
      {"hamlet", ContextPlaceKind::hamlet},     {"neighbourhood", ContextPlaceKind::neighbourhood},
      {"locality", ContextPlaceKind::locality}, {"island", ContextPlaceKind::island},
      {"islet", ContextPlaceKind::island}};
  for (const auto& entry : kPlaces)
    if (std::strcmp(place, entry.value) == 0) return entry.kind;
  return std::nullopt;
}

// The leading number of a population=* value, digit group separators (",", " ", "'", "_")
// skipped: "12,345" is 12345. Nothing when it does not start with a digit.
std::optional<std::uint64_t> population_of(const char* text) {
  if (!text || *text < '0' || *text > '9') return std::nullopt;
  std::uint64_t n = 0;
  for (const char* p = text; *p; ++p) {
    if (*p >= '0' && *p <= '9') {
      if (n > 1'000'000'000'000ULL) break;  // more people than there are: stop growing
      n = n * 10 + static_cast<std::uint64_t>(*p - '0');
    } else if (!std::strchr(", '_", *p)) {
      break;
    }
  }
  return n;
}

// model::ContextPlace::rank: the kind's rank, then a population step.
int place_rank(ContextPlaceKind kind, std::optional<std::uint64_t> population) {
  static constexpr int kKindRank[model::kContextPlaceKinds] = {
      0,  // city
      1,  // town
      3,  // village
      2,  // suburb
      6,  // hamlet
      5,  // neighbourhood
      7,  // locality
      4,  // island
  };
  int step = 8;
  if (population) {
    step = 7;
    for (std::uint64_t p = *population; p >= 10 && step > 0; p /= 10) --step;
  }
  return 10 * kKindRank[static_cast<std::size_t>(kind)] + step;
}

// libosmium's area assembler, for the relations manager: assembles only what area_kind_of
// keeps (closed ways with natural=coastline, say, pass the coarse key filter) and counts what
// fails to assemble, which the manager would otherwise drop silently.
class ContextAssembler {
 public:
  struct config_type : osmium::area::AssemblerConfig {
    std::size_t* failed = nullptr;  // incremented for every area of a kept kind that fails
  };

  explicit ContextAssembler(const config_type& config) : config_(config), assembler_(config) {}

  bool operator()(const osmium::Way& way, osmium::memory::Buffer& out) {
    return assemble(way.tags(), [&] { return assembler_(way, out); });
  }
  bool operator()(const osmium::Relation& relation, const std::vector<const osmium::Way*>& members,
                  osmium::memory::Buffer& out) {
    return assemble(relation.tags(), [&] { return assembler_(relation, members, out); });
  }
  const osmium::area::area_stats& stats() const noexcept { return assembler_.stats(); }

 private:
  template <class F>
  bool assemble(const osmium::TagList& tags, F&& run) {
    if (!area_kind_of(tags)) return true;
    bool ok = false;
    try {
      ok = run();
    } catch (const osmium::invalid_location&) {
      ok = false;
    }
    if (!ok && config_.failed) ++*config_.failed;
    return ok;
  }

  const config_type& config_;
  osmium::area::Assembler assembler_;
};

using AreaManager = osmium::area::MultipolygonManager<ContextAssembler>;

class ContextCollector : public osmium::handler::Handler {
 public:
  ContextCollector(OsmContextStats& stats, const ImportLimits& limits, const std::string& source)
      : stats_(stats), limits_(limits), source_(source) {}

  void relation_read() {
    ++stats_.osm_relations;
    check_limit(stats_.osm_relations, limits_.max_osm_relations, "max_osm_relations", where(), "relations in the file");
    tick();
  }

  void node(const osmium::Node& node) {
    ++stats_.osm_nodes;
    check_limit(stats_.osm_nodes, limits_.max_osm_nodes, "max_osm_nodes", where(), "nodes in the file");
    tick();
    if (!node.location().valid()) return;
    const geo::LonLat pos{node.location().lon(), node.location().lat()};
    node_box_.extend(pos);
    const auto kind = place_kind_of(tag_value(node.tags(), "place"));
    const char* name = kind ? tag_value(node.tags(), "name") : nullptr;
    if (!name || !*name) return;
    check_text(name, limits_.max_name_bytes, "max_name_bytes", object_where("node", node.id()), "name tag");
    keep_points(1, object_where("node", node.id()));
    layers_.places.push_back(
        {*kind, name, pos, place_rank(*kind, population_of(tag_value(node.tags(), "population")))});
    ++stats_.places[static_cast<std::size_t>(*kind)];
  }

  void way(const osmium::Way& way) {
    ++stats_.osm_ways;
    check_limit(stats_.osm_ways, limits_.max_osm_ways, "max_osm_ways", where(), "ways in the file");
    tick();
    if (is(tag_value(way.tags(), "natural"), "coastline")) add_coastline(way);
    if (const auto kind = line_kind_of(way.tags())) add_line(way, *kind);
    // The manager drops closed ways whose first or last node is missing before they reach the
    // assembler (which counts the other failures): counted here.
    const auto& nodes = way.nodes();
    if (nodes.size() > 3 && nodes.front().ref() == nodes.back().ref() &&
        (!nodes.front().location().valid() || !nodes.back().location().valid()) && area_kind_of(way.tags()))
      ++stats_.failed_areas;
  }

  // The areas libosmium assembled: one ContextArea per outer ring.
  void take_areas(const osmium::memory::Buffer& buffer) {
    for (const auto& area : buffer.select<osmium::Area>()) {
      const auto kind = area_kind_of(area.tags());
      if (!kind) continue;
      for (const auto& outer : area.outer_rings()) {
        model::ContextArea out{*kind, {ring_of(outer, true)}};
        if (out.rings.front().size() < 3) continue;
        for (const auto& inner : area.inner_rings(outer)) {
          auto ring = ring_of(inner, false);
          if (ring.size() >= 3) out.rings.push_back(std::move(ring));
        }
        std::size_t points = 0;
        for (const auto& ring : out.rings) points += ring.size();
        keep_points(points, object_where(area.from_way() ? "way" : "relation", area.orig_id()));
        layers_.areas.push_back(std::move(out));
        ++stats_.areas[static_cast<std::size_t>(*kind)];
      }
    }
  }

  // Closes the coastline into sea within `bounds` (the header's box, else the nodes' box).
  model::ContextLayers finish(const osmium::Box& header_box) && {
    geo::BBox bounds = node_box_;
    if (header_box.valid())
      bounds = {header_box.bottom_left().lon(), header_box.bottom_left().lat(), header_box.top_right().lon(),
                header_box.top_right().lat()};
    auto sea = sea_from_coastlines(coastline_, bounds);
    stats_.coastline_chains = sea.chains;
    stats_.islands = sea.islands;
    stats_.broken_coastline_chains = sea.broken_chains;
    std::vector<model::ContextArea> areas;
    for (auto& polygon : sea.seas) {
      model::ContextArea area{ContextAreaKind::sea, {std::move(polygon.outer)}};
      for (auto& hole : polygon.holes) area.rings.push_back(std::move(hole));
      std::size_t points = 0;
      for (const auto& ring : area.rings) points += ring.size();
      keep_points(points, source_ + " coastline");
      areas.push_back(std::move(area));
      ++stats_.areas[static_cast<std::size_t>(ContextAreaKind::sea)];
      ++stats_.sea_rings;
    }
    std::move(layers_.areas.begin(), layers_.areas.end(), std::back_inserter(areas));
    layers_.areas = std::move(areas);
    return std::move(layers_);
  }

  std::string where() const {
    return source_ + " after " + std::to_string(stats_.osm_nodes) + " nodes, " + std::to_string(stats_.osm_ways) +
           " ways and " + std::to_string(stats_.osm_relations) + " relations";
  }

 private:
  // Polls the stop token every 8,192 entities.
  void tick() {
    if (((stats_.osm_nodes + stats_.osm_ways + stats_.osm_relations) & 8191) == 0) util::check_stop();
  }
  std::string object_where(const char* type, osmium::object_id_type id) const {
    return source_ + " " + type + " " + std::to_string(id);
  }
  void keep_points(std::size_t n, const std::string& at) {
    stats_.points += n;
    check_limit(stats_.points, limits_.max_context_points, "max_context_points", at, "positions in the context layers");
  }

  // The pieces of a way between nodes missing from the extract (repeated nodes dropped), with
  // their node ids.
  template <class F>
  static void for_each_located_piece(const osmium::Way& way, F&& f) {
    std::vector<std::int64_t> ids;
    std::vector<geo::LonLat> points;
    auto flush = [&] {
      if (points.size() >= 2) f(ids, points);
      ids.clear();
      points.clear();
    };
    for (const auto& ref : way.nodes()) {
      if (!ref.location().valid()) {
        flush();
        continue;
      }
      if (!ids.empty() && ids.back() == ref.ref()) continue;
      ids.push_back(ref.ref());
      points.push_back({ref.location().lon(), ref.location().lat()});
    }
    flush();
  }

  void add_coastline(const osmium::Way& way) {
    for_each_located_piece(way, [&](std::vector<std::int64_t>& ids, std::vector<geo::LonLat>& points) {
      coastline_.push_back({std::move(ids), std::move(points)});
      ++stats_.coastline_ways;
    });
  }

  void add_line(const osmium::Way& way, ContextLineKind kind) {
    const char* name = tag_value(way.tags(), "name");
    if (name) check_text(name, limits_.max_name_bytes, "max_name_bytes", object_where("way", way.id()), "name tag");
    const char* tunnel = tag_value(way.tags(), "tunnel");
    for_each_located_piece(way, [&](std::vector<std::int64_t>&, std::vector<geo::LonLat>& points) {
      keep_points(points.size(), object_where("way", way.id()));
      layers_.lines.push_back({kind, name ? name : "", tunnel && !is(tunnel, "no"), std::move(points)});
      ++stats_.lines[static_cast<std::size_t>(kind)];
    });
  }

  // A ring's positions without the closing one, outer rings counter-clockwise, inner clockwise.
  static std::vector<geo::LonLat> ring_of(const osmium::NodeRefList& ring, bool outer) {
    std::vector<geo::LonLat> points;
    points.reserve(ring.size());
    for (const auto& ref : ring) points.push_back({ref.location().lon(), ref.location().lat()});
    if (points.size() >= 2 && points.front().lon == points.back().lon && points.front().lat == points.back().lat)
      points.pop_back();
    if ((signed_area2(points) > 0.0) != outer) std::reverse(points.begin(), points.end());
    return points;
  }

  OsmContextStats& stats_;
  const ImportLimits& limits_;
  const std::string& source_;
  model::ContextLayers layers_;
  std::vector<CoastlineWay> coastline_;
  geo::BBox node_box_;
};

// Pass 1: the multipolygon relations (of the kinds kept) go to the manager.
void read_relations(const osmium::io::File& file, AreaManager& manager, ContextCollector& collector,
                    OsmContextStats& stats) {
  osmium::io::Reader reader(file, osmium::osm_entity_bits::relation);
  while (osmium::memory::Buffer buffer = reader.read()) {
    util::check_stop();
    for (const auto& relation : buffer.select<osmium::Relation>()) {
      collector.relation_read();
      if (well_formed_tags(relation.tags()))
        manager.relation(relation);
      else
        ++stats.malformed_tags;
    }
  }
  reader.close();
  manager.prepare_for_lookup();
}

// Pass 2: nodes and ways; areas as the manager completes them.
osmium::Box read_nodes_and_ways(const osmium::io::File& file, AreaManager& manager, ContextCollector& collector,
                                OsmContextStats& stats) {
  osmium::io::Reader reader(file, osmium::osm_entity_bits::node | osmium::osm_entity_bits::way);
  const osmium::Box header_box = reader.header().box();
  LocationIndex index;
  LocationHandler locations(index);
  locations.ignore_errors();        // ways may reference nodes outside the extract
  auto& areas = manager.handler();  // no callback: the assembled areas are read after each buffer
  while (osmium::memory::Buffer buffer = reader.read()) {
    util::check_stop();
    osmium::apply(buffer, locations, collector);
    // Only ways with well-formed tags reach libosmium's tag walks (the filter, the assembler).
    for (const auto& way : buffer.select<osmium::Way>()) {
      if (well_formed_tags(way.tags()))
        areas.way(way);
      else
        ++stats.malformed_tags;
    }
    collector.take_areas(manager.read());
  }
  reader.close();
  collector.take_areas(manager.read());
  return header_box;
}

}  // namespace

model::ContextLayers load_osm_context(const std::string& path, OsmContextStats* stats_out, const ImportLimits& limits) {
  if (!std::filesystem::is_regular_file(path)) throw LoadError(path, "no such file");
  const std::string source = file_name(path);
  OsmContextStats stats;
  ContextCollector collector(stats, limits, source);
  try {
    const OsmInput input(path, limits, source);
    stats.input_bytes = input.input_bytes();
    util::check_stop();
    ContextAssembler::config_type config;
    config.create_empty_areas = false;  // a failed assembly returns false (counted) and writes nothing
    config.failed = &stats.failed_areas;
    AreaManager manager(config, area_keys());
    read_relations(input.file(), manager, collector, stats);
    const auto header_box = read_nodes_and_ways(input.file(), manager, collector, stats);
    manager.for_each_incomplete_relation([&](const osmium::relations::RelationHandle& relation) {
      if (area_kind_of(relation->tags())) ++stats.incomplete_relations;
    });
    auto layers = std::move(collector).finish(header_box);
    if (stats_out) *stats_out = stats;
    return layers;
  } catch (const LoadError&) {
    throw;  // LimitExceeded included
  } catch (const util::Stopped&) {
    throw;  // the request ended: not a problem of the file
  } catch (const std::exception& e) {
    // libosmium reports truncated/corrupt input (XML, PBF) as exceptions.
    throw LoadError(collector.where(), std::string("cannot read OSM data: ") + e.what());
  }
}

}  // namespace tourmap::load
