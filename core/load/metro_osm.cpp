#include "load/metro_osm.hpp"

#include "geo/projection.hpp"
#include "load/file.hpp"
#include "load/load_error.hpp"
#include "load/metro_builder.hpp"
#include "load/osm_input.hpp"
#include "load/strings.hpp"
#include "util/stop.hpp"

#include <osmium/handler.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/flex_mem.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/visitor.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>

namespace tourmap::load {
namespace {

using LocationIndex = osmium::index::map::FlexMem<osmium::unsigned_object_id_type, osmium::Location>;
using LocationHandler = osmium::handler::NodeLocationsForWays<LocationIndex>;

constexpr double kSameStationMetres = 400;   // stops of one name this close: one station
constexpr double kNamelessStopMetres = 150;  // a stop without a name joins a station this close
const std::vector<std::string> kModes = {"subway", "light_rail", "tram",      "train",      "monorail",
                                         "funicular", "bus",     "trolleybus", "ferry"};
const std::vector<std::string> kRailModes = {"subway", "light_rail", "tram", "train", "monorail", "funicular"};

std::string text(const osmium::TagList& tags, const char* key) {
  const char* value = tag_value(tags, key);
  return value ? value : "";
}

// "#1f77b4" or "1F77B4" -> "1f77b4"; anything else (named colours) -> "".
std::string colour_of(const std::string& value) {
  std::string hex = value.size() == 7 && value[0] == '#' ? value.substr(1) : value;
  if (hex.size() != 6 || !std::all_of(hex.begin(), hex.end(), [](unsigned char c) { return std::isxdigit(c); }))
    return "";
  return ascii_lower(hex);
}

// A stop or platform member of a route: 'n' or 'w' and the OSM id.
using ObjectKey = std::pair<char, osmium::object_id_type>;

struct Route {
  osmium::object_id_type id;
  std::string mode, ref, name, colour;
  std::vector<ObjectKey> stops;      // stop positions (role stop*), in member order
  std::vector<ObjectKey> platforms;  // platforms (role platform*), in member order
};

struct Master {
  std::string ref, name, colour;
  std::vector<osmium::object_id_type> routes;
};

struct Stop {
  geo::LonLat pos;
  std::string name;
};

bool is_stop_role(const char* role) { return std::strncmp(role, "stop", 4) == 0; }
bool is_platform_role(const char* role) { return std::strncmp(role, "platform", 8) == 0; }

// Pass 1: routes of every mode known, route masters, stop areas.
struct RelationPass {
  std::vector<Route> routes;
  std::unordered_map<osmium::object_id_type, Master> masters;
  std::map<ObjectKey, osmium::object_id_type> area_of;        // stop -> its stop area
  std::unordered_map<osmium::object_id_type, std::string> area_names;
  std::size_t read = 0;
};

void read_relations(const osmium::io::File& file, RelationPass& pass, const ImportLimits& limits,
                    const std::string& source, OsmTransitStats& stats) {
  osmium::io::Reader reader(file, osmium::osm_entity_bits::relation);
  while (osmium::memory::Buffer buffer = reader.read()) {
    util::check_stop();
    for (const auto& relation : buffer.select<osmium::Relation>()) {
      ++pass.read;
      check_limit(pass.read, limits.max_osm_relations, "max_osm_relations", source, "relations in the file");
      if ((pass.read & 8191) == 0) util::check_stop();
      const auto& tags = relation.tags();
      if (!well_formed_tags(tags)) continue;
      const std::string type = text(tags, "type");
      const std::string where = source + " relation " + std::to_string(relation.id());
      for (const char* key : {"ref", "name"})
        check_text(text(tags, key), limits.max_name_bytes, "max_name_bytes", where, std::string(key) + " tag");
      if (type == "route") {
        const std::string mode = text(tags, "route");
        if (std::find(kModes.begin(), kModes.end(), mode) == kModes.end()) continue;
        Route route{relation.id(), mode, text(tags, "ref"), text(tags, "name"), colour_of(text(tags, "colour")), {}, {}};
        for (const auto& member : relation.members()) {
          if (member.type() != osmium::item_type::node && member.type() != osmium::item_type::way) continue;
          const ObjectKey key{member.type() == osmium::item_type::node ? 'n' : 'w', member.ref()};
          if (is_stop_role(member.role())) route.stops.push_back(key);
          else if (is_platform_role(member.role())) route.platforms.push_back(key);
        }
        pass.routes.push_back(std::move(route));
      } else if (type == "route_master") {
        Master master{text(tags, "ref"), text(tags, "name"), colour_of(text(tags, "colour")), {}};
        for (const auto& member : relation.members())
          if (member.type() == osmium::item_type::relation) master.routes.push_back(member.ref());
        pass.masters.emplace(relation.id(), std::move(master));
      } else if (text(tags, "public_transport") == "stop_area") {
        pass.area_names[relation.id()] = text(tags, "name");
        for (const auto& member : relation.members())
          if (member.type() == osmium::item_type::node || member.type() == osmium::item_type::way)
            pass.area_of.emplace(ObjectKey{member.type() == osmium::item_type::node ? 'n' : 'w', member.ref()},
                                 relation.id());
      }
    }
  }
  reader.close();
  stats.routes = pass.routes.size();
}

// Pass 2: the stops' positions and names.
class StopCollector : public osmium::handler::Handler {
 public:
  StopCollector(const std::set<ObjectKey>& wanted, const ImportLimits& limits, const std::string& source)
      : wanted_(wanted), limits_(limits), source_(source) {}

  void node(const osmium::Node& node) {
    check_limit(++nodes_, limits_.max_osm_nodes, "max_osm_nodes", source_, "nodes in the file");
    tick();
    if (!node.location().valid() || !wanted_.count({'n', node.id()})) return;
    add({'n', node.id()}, {node.location().lon(), node.location().lat()}, node.tags());
  }

  void way(const osmium::Way& way) {
    check_limit(++ways_, limits_.max_osm_ways, "max_osm_ways", source_, "ways in the file");
    tick();
    if (!wanted_.count({'w', way.id()})) return;
    if (const auto centre = way_centre(way)) add({'w', way.id()}, *centre, way.tags());
  }

  std::map<ObjectKey, Stop> stops;

 private:
  void tick() {
    if (((nodes_ + ways_) & 8191) == 0) util::check_stop();
  }
  void add(ObjectKey key, geo::LonLat pos, const osmium::TagList& tags) {
    std::string name = well_formed_tags(tags) ? text(tags, "name") : "";
    check_text(name, limits_.max_name_bytes, "max_name_bytes",
               source_ + (key.first == 'n' ? " node " : " way ") + std::to_string(key.second), "name tag");
    stops.emplace(key, Stop{pos, std::move(name)});
  }

  const std::set<ObjectKey>& wanted_;
  const ImportLimits& limits_;
  const std::string& source_;
  std::size_t nodes_ = 0, ways_ = 0;
};

// Metres east and north of `origin` (an equirectangular frame: fine over a few kilometres).
std::pair<double, double> metres_from(geo::LonLat origin, geo::LonLat p) {
  constexpr double kMetresPerDegree = 111'320.0;
  return {(p.lon - origin.lon) * kMetresPerDegree * std::cos(origin.lat * 3.14159265358979323846 / 180.0),
          (p.lat - origin.lat) * kMetresPerDegree};
}

// Drops an edge u-w whose every line also runs from u to w through at most kMaxSkipped other
// stations lying along it (within a quarter of |uw| of the segment): one direction of a route
// (or one route of a line) that lists fewer stops than the other, or an express that skips
// stops, would otherwise draw a chord beside the track (Liechtenstein's R2: Schaanwald straight
// to Schaan-Vaduz beside Schaanwald - Nendeln - Forst Hilti - Schaan-Vaduz). Returns how many.
constexpr std::size_t kMaxSkipped = 6;
std::size_t drop_skip_edges(model::MetroNetwork& net) {
  std::size_t dropped = 0;
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<std::vector<std::pair<std::uint32_t, std::size_t>>> adjacent(net.nodes.size());  // (node, edge)
    for (std::size_t e = 0; e < net.edges.size(); ++e) {
      adjacent[net.edges[e].from].push_back({net.edges[e].to, e});
      adjacent[net.edges[e].to].push_back({net.edges[e].from, e});
    }
    const auto carries = [&](std::size_t e, const std::vector<std::uint32_t>& lines) {
      const auto& on = net.edges[e].lines;
      return std::all_of(lines.begin(), lines.end(), [&](auto l) { return std::find(on.begin(), on.end(), l) != on.end(); });
    };
    for (std::size_t e = 0; e < net.edges.size() && !changed; ++e) {
      const auto u = net.edges[e].from, w = net.edges[e].to;
      const auto origin = net.nodes[u].pos;
      const auto end = metres_from(origin, net.nodes[w].pos);
      const double wx = end.first, wy = end.second;  // not a structured binding: lambdas capture these
      const double length = std::hypot(wx, wy);
      if (length <= 0) continue;
      const auto along = [&](std::uint32_t v) {  // near the segment u-w
        const auto [x, y] = metres_from(origin, net.nodes[v].pos);
        const double t = std::clamp((x * wx + y * wy) / (length * length), 0.0, 1.0);
        return std::hypot(x - t * wx, y - t * wy) <= 0.25 * length;
      };
      // Breadth first from u over edges carrying e's lines, through nodes along u-w, not e itself.
      std::vector<int> depth(net.nodes.size(), -1);
      std::vector<std::uint32_t> frontier{u};
      depth[u] = 0;
      bool found = false;
      for (std::size_t d = 0; d <= kMaxSkipped && !frontier.empty() && !found; ++d) {
        std::vector<std::uint32_t> next;
        for (const auto v : frontier)
          for (const auto& [x, edge] : adjacent[v]) {
            if (edge == e || depth[x] >= 0 || !carries(edge, net.edges[e].lines)) continue;
            if (x == w) {
              found = d >= 1;  // at least one station between
              continue;
            }
            if (!along(x)) continue;
            depth[x] = static_cast<int>(d) + 1;
            next.push_back(x);
          }
        frontier = std::move(next);
      }
      if (found) {
        net.edges.erase(net.edges.begin() + static_cast<std::ptrdiff_t>(e));
        ++dropped;
        changed = true;
      }
    }
  }
  return dropped;
}

struct Station {
  std::string id, name;
  double lon = 0, lat = 0;  // sums, then the mean
  std::size_t stops = 0;
  geo::LonLat first;
};

}  // namespace

std::vector<std::string> default_transit_modes(const std::vector<std::string>& present) {
  std::vector<std::string> rail;
  for (const auto& mode : kRailModes)
    if (std::find(present.begin(), present.end(), mode) != present.end()) rail.push_back(mode);
  return rail.empty() ? std::vector<std::string>{"bus"} : rail;
}

model::MetroNetwork load_metro_osm(const std::string& path, const std::vector<std::string>& asked,
                                   const ImportLimits& limits, OsmTransitStats* stats_out) {
  if (!std::filesystem::is_regular_file(path)) throw LoadError(path, "no such file");
  const std::string source = file_name(path);
  for (const auto& mode : asked)
    if (std::find(kModes.begin(), kModes.end(), mode) == kModes.end())
      throw LoadError(source, "unknown transit mode '" + mode + "'");
  OsmTransitStats stats;
  try {
    const OsmInput input(path, limits, source);
    RelationPass pass;
    read_relations(input.file(), pass, limits, source, stats);
    std::vector<std::string> present;
    for (const auto& route : pass.routes)
      if (std::find(present.begin(), present.end(), route.mode) == present.end()) present.push_back(route.mode);
    stats.modes = asked.empty() ? default_transit_modes(present) : asked;
    std::erase_if(pass.routes, [&](const Route& r) {
      return std::find(stats.modes.begin(), stats.modes.end(), r.mode) == stats.modes.end();
    });
    stats.routes = pass.routes.size();

    std::set<ObjectKey> wanted;
    for (const auto& route : pass.routes) {
      wanted.insert(route.stops.begin(), route.stops.end());
      wanted.insert(route.platforms.begin(), route.platforms.end());
    }
    StopCollector collector(wanted, limits, source);
    {
      osmium::io::Reader reader(input.file(), osmium::osm_entity_bits::node | osmium::osm_entity_bits::way);
      LocationIndex index;
      LocationHandler locations(index);
      locations.ignore_errors();
      while (osmium::memory::Buffer buffer = reader.read()) {
        util::check_stop();
        osmium::apply(buffer, locations, collector);
      }
      reader.close();
    }
    stats.stops = collector.stops.size();
    stats.missing_stop_members = wanted.size() - collector.stops.size();

    // Stations: by stop area, then by name within kSameStationMetres.
    std::vector<Station> stations;
    std::map<ObjectKey, std::size_t> station_of;
    std::unordered_map<osmium::object_id_type, std::size_t> station_of_area;
    std::unordered_map<std::string, std::vector<std::size_t>> stations_by_name;
    const auto add_to = [&](std::size_t s, const ObjectKey& key, const Stop& stop) {
      auto& st = stations[s];
      st.lon += stop.pos.lon;
      st.lat += stop.pos.lat;
      ++st.stops;
      station_of[key] = s;
    };
    const auto new_station = [&](const ObjectKey& key, const Stop& stop, std::string name) {
      stations.push_back({std::string("s") + key.first + std::to_string(key.second), std::move(name), 0, 0, 0, stop.pos});
      if (!stations.back().name.empty()) stations_by_name[ascii_lower(stations.back().name)].push_back(stations.size() - 1);
      return stations.size() - 1;
    };
    for (const auto& [key, stop] : collector.stops) {
      const auto area = pass.area_of.find(key);
      if (area == pass.area_of.end()) continue;
      auto [it, fresh] = station_of_area.emplace(area->second, 0);
      if (fresh) {
        const auto& area_name = pass.area_names[area->second];
        it->second = new_station(key, stop, area_name.empty() ? stop.name : area_name);
      }
      add_to(it->second, key, stop);
    }
    // A platform named by its track ("1", "2a") is named as no station is.
    const auto station_name = [](const std::string& name) { return name.size() > 2 ? name : std::string(); };
    for (const auto& [key, stop] : collector.stops) {
      if (station_of.count(key) || station_name(stop.name).empty()) continue;
      std::optional<std::size_t> into;
      if (auto it = stations_by_name.find(ascii_lower(stop.name)); it != stations_by_name.end())
        for (auto s : it->second)
          if (!into && geo::geodesic_distance_m(stations[s].first, stop.pos) <= kSameStationMetres) into = s;
      add_to(into ? *into : new_station(key, stop, stop.name), key, stop);
    }
    // Stops without a station name: the nearest station within kNamelessStopMetres, else their own.
    const std::size_t named_stations = stations.size();
    for (const auto& [key, stop] : collector.stops) {
      if (station_of.count(key)) continue;
      std::optional<std::size_t> into;
      double best = kNamelessStopMetres;
      for (std::size_t s = 0; s < named_stations; ++s)
        if (const double d = geo::geodesic_distance_m(stations[s].first, stop.pos); d <= best) {
          best = d;
          into = s;
        }
      add_to(into ? *into : new_station(key, stop, ""), key, stop);
    }

    // Lines and their edges.
    MetroBuilder builder(limits);
    std::unordered_map<osmium::object_id_type, osmium::object_id_type> master_of;
    for (const auto& [id, master] : pass.masters)
      for (auto route : master.routes) master_of[route] = id;
    std::vector<std::optional<std::uint32_t>> node_of_station(stations.size());
    const auto node_of = [&](std::size_t s) {
      if (!node_of_station[s]) {
        auto& st = stations[s];
        const geo::LonLat pos{st.lon / static_cast<double>(st.stops), st.lat / static_cast<double>(st.stops)};
        const std::string name = st.name.empty() ? "Stop " + st.id.substr(2) : st.name;
        node_of_station[s] = builder.add_node({st.id, st.id, name, pos}, source + " station " + st.id);
        ++stats.stations;
      }
      return *node_of_station[s];
    };
    // Routes without a master: one line per mode and ref (the two directions of a route are
    // often two relations with no master over them), else one per route.
    std::map<std::pair<std::string, std::string>, osmium::object_id_type> line_of_ref;
    std::set<osmium::object_id_type> masters_used;
    for (const auto& route : pass.routes) {
      // The stations in the order of the stop positions, or of the platforms where fewer than
      // two stop positions are in the extract (mappers often list all stops, then all platforms).
      const auto sequence_of = [&](const std::vector<ObjectKey>& keys) {
        std::vector<std::size_t> sequence;
        for (const auto& key : keys)
          if (auto it = station_of.find(key); it != station_of.end() && (sequence.empty() || sequence.back() != it->second))
            sequence.push_back(it->second);
        return sequence;
      };
      auto sequence = sequence_of(route.stops);
      if (sequence.size() < 2) sequence = sequence_of(route.platforms);
      if (sequence.size() < 2) {
        ++stats.routes_without_stops;
        continue;
      }
      model::MetroLine line;
      const auto master = master_of.find(route.id);
      if (master != master_of.end()) {
        const auto& m = pass.masters.at(master->second);
        line.id = "r" + std::to_string(master->second);
        line.label = !m.ref.empty() ? m.ref : !route.ref.empty() ? route.ref : !m.name.empty() ? m.name : route.name;
        line.color = !m.colour.empty() ? m.colour : route.colour;
        masters_used.insert(master->second);
      } else {
        const auto first = route.ref.empty() ? route.id : line_of_ref.emplace(std::pair{route.mode, route.ref}, route.id).first->second;
        line.id = "r" + std::to_string(first);
        line.label = !route.ref.empty() ? route.ref : route.name;
        line.color = route.colour;
      }
      if (line.label.empty()) line.label = line.id;
      const auto where = source + " relation " + std::to_string(route.id);
      const auto l = builder.line(line, where);
      for (std::size_t i = 0; i + 1 < sequence.size(); ++i) builder.connect(node_of(sequence[i]), node_of(sequence[i + 1]), l, where);
    }
    stats.route_masters = masters_used.size();
    if (stats.stations == 0) {
      std::string modes;
      for (const auto& m : stats.modes) modes += (modes.empty() ? "" : ", ") + m;
      throw LoadError(source, "no route of the modes " + modes + " has two stops in the extract (" +
                                  std::to_string(stats.routes) + " routes)");
    }
    auto net = std::move(builder).finish(source);
    stats.skip_edges = drop_skip_edges(net);
    if (stats_out) *stats_out = stats;
    return net;
  } catch (const LoadError&) {
    throw;
  } catch (const util::Stopped&) {
    throw;
  } catch (const std::exception& e) {
    throw LoadError(source, std::string("cannot read OSM data: ") + e.what());
  }
}

}  // namespace tourmap::load
