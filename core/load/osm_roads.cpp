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
#include <optional>
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

// Checks a PBF's blobs before libosmium decodes them (it bounds each blob, not their number).
void check_pbf(std::string_view pbf, const ImportLimits& limits, const std::string& source, OsmRoadStats& stats) {
  const auto blobs = scan_pbf_blobs(pbf, limits.max_osm_pbf_blobs, limits.max_osm_decompressed_bytes);
  check_limit(blobs.count, limits.max_osm_pbf_blobs, "max_osm_pbf_blobs", source, "PBF blobs");
  check_limit(blobs.raw_bytes, limits.max_osm_decompressed_bytes, "max_osm_decompressed_bytes", source,
              "bytes of OSM data after decompression (the sum of the PBF blobs' sizes)");
  stats.input_bytes = blobs.raw_bytes;
}

// The libosmium format of the (decompressed) text of an extract.
std::string plain_format(const osmium::io::File& file, const std::string& source) {
  switch (file.format()) {
    case osmium::io::file_format::xml: return "osm";
    case osmium::io::file_format::opl: return "opl";
    case osmium::io::file_format::o5m: return "o5m";
    default: throw LoadError(source, "unsupported OSM format (expected .osm, .osm.gz, .osm.bz2 or .osm.pbf)");
  }
}

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
    osmium::io::File file(path);
    // libosmium reads a .pbf through a descriptor of its own that it closes only after a
    // successful read: every PBF that failed to parse leaked one (a server importing uploads
    // would run out). A PBF is therefore read from memory: no descriptor to leak. Its blobs are
    // counted and their sizes summed first.
    std::string pbf;
    // Compressed XML is decompressed here, bounded and stoppable, into an unlinked temporary
    // file that libosmium then reads as plain XML (its own decompression has no bound).
    std::optional<SpoolFile> spool;
    if (file.format() == osmium::io::file_format::pbf) {
      pbf = read_file(path);
      check_pbf(pbf, limits, source, stats);
      file = osmium::io::File(pbf.data(), pbf.size(), "pbf");
    } else if (file.compression() == osmium::io::file_compression::none ||
               (file.compression() == osmium::io::file_compression::gzip && !starts_like_gzip(path))) {
      // Plain text (zlib's gzread, which libosmium uses, passes a .gz that is not gzip through).
      stats.input_bytes = std::filesystem::file_size(path);
      check_limit(stats.input_bytes, limits.max_osm_decompressed_bytes, "max_osm_decompressed_bytes", source,
                  "bytes of OSM data");
      file = osmium::io::File(path, plain_format(file, source));
    } else {
      const auto format = plain_format(file, source);
      spool.emplace();
      stats.input_bytes = decompress_osm(
          path, file.compression() == osmium::io::file_compression::gzip ? OsmCompression::gzip : OsmCompression::bzip2,
          *spool, limits.max_osm_decompressed_bytes, source);
      file = osmium::io::File(spool->path(), format);
    }
    util::check_stop();
    osmium::io::Reader reader(file, osmium::osm_entity_bits::node | osmium::osm_entity_bits::way);
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
