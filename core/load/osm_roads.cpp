#include "load/osm_roads.hpp"

#include "load/file.hpp"
#include "load/load_error.hpp"

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

// The value of tag `key`, or nullptr, reading the tag list's bytes (key NUL value NUL ...)
// strictly within the list. TagList::operator[] walks the list with strchr and trusts its
// shape, but libosmium's PBF reader copies string-table entries with NUL bytes inside them as
// they are: the walk then gets out of step and runs past the end of the list (a heap overread
// on a crafted .osm.pbf). Here such a list simply ends at its last complete pair.
const char* tag_value(const osmium::TagList& tags, const char* key) {
  const char* p = reinterpret_cast<const char*>(tags.data()) + sizeof(osmium::TagList);
  const char* const end = reinterpret_cast<const char*>(tags.data()) + tags.byte_size();
  while (p < end) {
    const auto* key_end = static_cast<const char*>(std::memchr(p, '\0', static_cast<std::size_t>(end - p)));
    if (!key_end || key_end + 1 >= end) return nullptr;
    const char* value = key_end + 1;
    const auto* value_end = static_cast<const char*>(std::memchr(value, '\0', static_cast<std::size_t>(end - value)));
    if (!value_end) return nullptr;
    if (std::strcmp(p, key) == 0) return value;
    p = value_end + 1;
  }
  return nullptr;
}

class RoadCollector : public osmium::handler::Handler {
 public:
  explicit RoadCollector(OsmRoadStats& stats) : stats_(stats) {}

  void node(const osmium::Node&) { ++stats_.osm_nodes; }

  void way(const osmium::Way& way) {
    ++stats_.osm_ways;
    const char* highway = tag_value(way.tags(), "highway");
    if (!highway) return;
    const char* area = tag_value(way.tags(), "area");
    if (!is_road_class(highway) || (area && std::strcmp(area, "yes") == 0)) {
      ++stats_.skipped_ways;
      return;
    }
    const char* name = tag_value(way.tags(), "name");
    model::RoadWay piece;
    auto flush = [&] {
      if (piece.nodes.size() >= 2) net_.ways.push_back(piece);
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
      piece.nodes.push_back(node_index(ref));
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
  std::uint32_t node_index(const osmium::NodeRef& ref) {
    auto [it, inserted] = index_.emplace(ref.ref(), static_cast<std::uint32_t>(net_.nodes.size()));
    if (inserted) net_.nodes.push_back({ref.ref(), {ref.location().lon(), ref.location().lat()}});
    return it->second;
  }

  OsmRoadStats& stats_;
  model::RoadNetwork net_;
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

model::RoadNetwork load_osm_roads(const std::string& path, OsmRoadStats* stats_out) {
  if (!std::filesystem::is_regular_file(path)) throw LoadError(path, "no such file");
  OsmRoadStats stats;
  try {
    // libosmium reads a .pbf through a descriptor of its own that it closes only after a
    // successful read: every PBF that failed to parse leaked one (a server importing uploads
    // would run out). A PBF is therefore read from memory: no descriptor to leak.
    osmium::io::File file(path);
    std::string pbf;
    if (file.format() == osmium::io::file_format::pbf) {
      pbf = read_file(path);
      file = osmium::io::File(pbf.data(), pbf.size(), "pbf");
    }
    osmium::io::Reader reader(file, osmium::osm_entity_bits::node | osmium::osm_entity_bits::way);
    LocationIndex index;
    LocationHandler locations(index);
    locations.ignore_errors();  // ways may reference nodes outside the extract
    RoadCollector collector(stats);
    osmium::apply(reader, locations, collector);
    reader.close();
    auto net = std::move(collector).take();
    if (net.ways.empty()) throw LoadError(file_name(path), "no highway ways in the file");
    if (stats_out) *stats_out = stats;
    return net;
  } catch (const LoadError&) {
    throw;
  } catch (const std::exception& e) {
    // libosmium reports truncated/corrupt input (gzip, bzip2, XML, PBF) as exceptions.
    throw LoadError(file_name(path) + " after " + std::to_string(stats.osm_nodes) + " nodes and " +
                        std::to_string(stats.osm_ways) + " ways",
                    std::string("cannot read OSM data: ") + e.what());
  }
}

}  // namespace tourmap::load
