#include "load/osm_roads.hpp"

#include "load/file.hpp"
#include "load/load_error.hpp"
#include "load/osm_input.hpp"
#include "util/stop.hpp"

#include <osmium/handler.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/flex_mem.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/visitor.hpp>

#include <cstring>
#include <filesystem>
#include <unordered_map>

namespace tourmap::load {
namespace {

using LocationIndex = osmium::index::map::FlexMem<osmium::unsigned_object_id_type, osmium::Location>;
using LocationHandler = osmium::handler::NodeLocationsForWays<LocationIndex>;

class RoadCollector : public osmium::handler::Handler {
 public:
  RoadCollector(OsmRoadStats& stats, const ImportLimits& limits, const std::string& source)
      : stats_(stats), limits_(limits), source_(source) {}

  void node(const osmium::Node&) {
    ++stats_.osm_nodes;
    check_limit(stats_.osm_nodes, limits_.max_osm_nodes, "max_osm_nodes", where(), "nodes in the file");
    tick();
  }

  void way(const osmium::Way& way) {
    ++stats_.osm_ways;
    check_limit(stats_.osm_ways, limits_.max_osm_ways, "max_osm_ways", where(), "ways in the file");
    tick();
    const char* highway = tag_value(way.tags(), "highway");
    if (!highway) return;
    const char* area = tag_value(way.tags(), "area");
    if (!is_road_class(highway) || (area && std::strcmp(area, "yes") == 0)) {
      ++stats_.skipped_ways;
      return;
    }
    const char* name = tag_value(way.tags(), "name");
    check_text(highway, limits_.max_name_bytes, "max_name_bytes", way_where(way), "highway tag");
    if (name) check_text(name, limits_.max_name_bytes, "max_name_bytes", way_where(way), "name tag");
    model::RoadWay piece;
    auto flush = [&] {
      if (piece.nodes.size() >= 2) {
        check_limit(net_.ways.size() + 1, limits_.max_road_ways, "max_road_ways", way_where(way), "road ways");
        edges_ += piece.nodes.size() - 1;
        check_limit(edges_, limits_.max_road_edges, "max_road_edges", way_where(way), "road edges");
        net_.ways.push_back(piece);
      }
      piece.nodes.clear();
    };
    piece.osm_id = way.id();
    piece.highway = highway;
    piece.name = name ? name : "";
    std::int64_t previous = 0;
    bool kept = false;
    for (const auto& ref : way.nodes()) {
      if (!ref.location().valid()) {  // node not in the extract: split the way here
        ++stats_.missing_nodes;
        kept |= piece.nodes.size() >= 2;
        flush();
        previous = 0;
        continue;
      }
      if (ref.ref() == previous) continue;  // repeated node
      previous = ref.ref();
      piece.nodes.push_back(node_index(ref, way));
    }
    kept |= piece.nodes.size() >= 2;
    flush();
    if (kept) ++stats_.highway_ways; else ++stats_.skipped_ways;
  }

  model::RoadNetwork take() && {
    net_.edges = model::edges_of(net_.ways);
    return std::move(net_);
  }

 private:
  // Polls the stop token every 8,192 entities.
  void tick() {
    if (((stats_.osm_nodes + stats_.osm_ways) & 8191) == 0) util::check_stop();
  }
  std::string where() const {
    return source_ + " after " + std::to_string(stats_.osm_nodes) + " nodes and " + std::to_string(stats_.osm_ways) +
           " ways";
  }
  std::string way_where(const osmium::Way& way) const { return source_ + " way " + std::to_string(way.id()); }

  std::uint32_t node_index(const osmium::NodeRef& ref, const osmium::Way& way) {
    if (auto it = index_.find(ref.ref()); it != index_.end()) return it->second;
    check_limit(net_.nodes.size() + 1, limits_.max_road_nodes, "max_road_nodes", way_where(way), "road nodes");
    const auto index = static_cast<std::uint32_t>(net_.nodes.size());
    index_.emplace(ref.ref(), index);
    net_.nodes.push_back({ref.ref(), {ref.location().lon(), ref.location().lat()}});
    return index;
  }

  OsmRoadStats& stats_;
  const ImportLimits& limits_;
  const std::string& source_;
  model::RoadNetwork net_;
  std::size_t edges_ = 0;
  std::unordered_map<std::int64_t, std::uint32_t> index_;
};

}  // namespace

bool is_road_class(const char* highway) {
  static const char* const kExcluded[] = {"proposed", "construction", "abandoned", "platform", "razed",
                                          "disused",  "no",           "elevator",  "corridor", "bus_stop",
                                          "rest_area", "services",    "emergency_bay"};
  if (!highway || !*highway) return false;
  for (const char* excluded : kExcluded)
    if (std::strcmp(highway, excluded) == 0) return false;
  return true;
}

model::RoadNetwork load_osm_roads(const std::string& path, OsmRoadStats* stats_out, const ImportLimits& limits) {
  if (!std::filesystem::is_regular_file(path)) throw LoadError(path, "no such file");
  const std::string source = file_name(path);
  OsmRoadStats stats;
  try {
    // The PBF read into memory, or compressed XML decompressed into a temporary file, both
    // bounded and stoppable (osm_input.hpp).
    const OsmInput input(path, limits, source);
    stats.input_bytes = input.input_bytes();
    util::check_stop();
    osmium::io::Reader reader(input.file(), osmium::osm_entity_bits::node | osmium::osm_entity_bits::way);
    LocationIndex index;
    LocationHandler locations(index);
    locations.ignore_errors();  // ways may reference nodes outside the extract
    RoadCollector collector(stats, limits, source);
    while (osmium::memory::Buffer buffer = reader.read()) {
      util::check_stop();
      osmium::apply(buffer, locations, collector);
    }
    reader.close();
    auto net = std::move(collector).take();
    if (net.ways.empty()) throw LoadError(source, "no highway ways in the file");
    if (stats_out) *stats_out = stats;
    return net;
  } catch (const LoadError&) {
    throw;  // LimitExceeded included
  } catch (const util::Stopped&) {
    throw;  // the request ended: not a problem of the file
  } catch (const std::exception& e) {
    // libosmium reports truncated/corrupt input (XML, PBF) as exceptions.
    throw LoadError(source + " after " + std::to_string(stats.osm_nodes) + " nodes and " +
                        std::to_string(stats.osm_ways) + " ways",
                    std::string("cannot read OSM data: ") + e.what());
  }
}

}  // namespace tourmap::load
