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
#include <unordered_set>

namespace tourmap::load {
namespace {

using LocationIndex = osmium::index::map::FlexMem<osmium::unsigned_object_id_type, osmium::Location>;
using LocationHandler = osmium::handler::NodeLocationsForWays<LocationIndex>;

constexpr double kSameStationMetres = 400;   // stops of one name this close: one station
constexpr double kNamelessStopMetres = 150;  // a stop without a name joins a station this close
constexpr double kStreetNameMetres = 60;     // else it takes the name of a track way this close
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

// A way of a route's track (a way member that is no stop or platform) and its role ("",
// "forward", "backward", ...).
struct TrackMember {
  osmium::object_id_type way;
  std::string role;
};

// Which way along its track a route serves a stop: older routes serving both directions in one
// relation mark the stops of each (roles forward_stop, backward_stop) and list the stops of the
// way back, in their order, after those of the way out. A bit set.
enum Direction : unsigned char { kForward = 1, kBackward = 2, kBothWays = 3 };

struct Route {
  osmium::object_id_type id = 0;
  std::string mode, ref, name, colour;
  std::vector<ObjectKey> stops;        // stop positions (role stop*), in member order
  std::vector<ObjectKey> platforms;    // platforms (role platform*), in member order
  std::vector<ObjectKey> other_nodes;  // node members of other roles: an older route's stops (role "")
  std::vector<TrackMember> track;      // way members of other roles, in member order
  std::set<ObjectKey> backward;        // stops and platforms of role backward_*
  bool both_ways = false;              // some are: the others without forward_ serve both directions
  std::set<ObjectKey> forward;         // stops and platforms of role forward_*

  unsigned char direction(const ObjectKey& key) const {
    if (!both_ways) return kForward;
    const bool out = forward.count(key) != 0, back = backward.count(key) != 0;
    return out == back ? kBothWays : out ? kForward : kBackward;
  }
};

// "relation 123 (bus 11)": how a problem names its route.
std::string route_label(const Route& route) {
  const std::string& what = !route.ref.empty() ? route.ref : route.name;
  return "relation " + std::to_string(route.id) + " (" + route.mode + (what.empty() ? "" : " " + what) + ")";
}

struct Master {
  std::string ref, name, colour;
  std::vector<osmium::object_id_type> routes;
};

struct Stop {
  geo::LonLat pos;
  std::string name;
};

// A member's role without its direction prefix ("forward_", "backward:", ...), and the direction.
std::pair<std::string_view, unsigned char> role_direction(std::string_view role) {
  for (const auto& [prefix, direction] : {std::pair{"forward", kForward}, std::pair{"backward", kBackward}})
    if (role.starts_with(prefix) && role.size() > std::strlen(prefix) &&
        (role[std::strlen(prefix)] == '_' || role[std::strlen(prefix)] == ':'))
      return {role.substr(std::strlen(prefix) + 1), direction};
  return {role, kBothWays};
}
bool is_stop_role(std::string_view role) { return role.starts_with("stop"); }
bool is_platform_role(std::string_view role) { return role.starts_with("platform"); }

// Pass 1: routes of every mode known, route masters, stop areas.
struct RelationPass {
  std::vector<Route> routes;
  std::unordered_map<osmium::object_id_type, Master> masters;
  std::map<ObjectKey, osmium::object_id_type> area_of;        // stop -> its stop area
  std::unordered_map<osmium::object_id_type, std::string> area_names;
  std::size_t read = 0;
};

// The track's work against max_osm_track_points: way members read, node positions held, track
// positions assembled, and positions gone over again (repairs at breaks, stations placed on the
// track, simplification), so a hostile relation cannot make the work grow beyond the limit.
class TrackBudget {
 public:
  TrackBudget(const ImportLimits& limits, const std::string& source)
      : limit_(limits.max_osm_track_points), source_(source) {}
  void add(std::size_t n) {
    used_ += n;
    check_limit(used_, limit_, "max_osm_track_points", source_,
                "track positions (route ways, their nodes, the tracks assembled and searched)");
  }
  std::size_t used() const { return used_; }

 private:
  std::size_t limit_;
  const std::string& source_;
  std::size_t used_ = 0;
};

void read_relations(const osmium::io::File& file, RelationPass& pass, const ImportLimits& limits,
                    const std::string& source, OsmTransitStats& stats, TrackBudget& budget) {
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
        Route route;
        route.id = relation.id();
        route.mode = mode;
        route.ref = text(tags, "ref");
        route.name = text(tags, "name");
        route.colour = colour_of(text(tags, "colour"));
        for (const auto& member : relation.members()) {
          if (member.type() != osmium::item_type::node && member.type() != osmium::item_type::way) continue;
          const ObjectKey key{member.type() == osmium::item_type::node ? 'n' : 'w', member.ref()};
          const auto [role, direction] = role_direction(member.role());
          const bool stop = is_stop_role(role), platform = is_platform_role(role);
          if (stop || platform) {
            (stop ? route.stops : route.platforms).push_back(key);
            if (direction == kBackward) route.backward.insert(key);
            if (direction == kForward) route.forward.insert(key);
          } else if (key.first == 'n') {
            route.other_nodes.push_back(key);
          } else {
            budget.add(1);
            route.track.push_back({member.ref(), member.role()});
          }
        }
        route.both_ways = !route.backward.empty();
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

// --- Track geometry (the header's "Edge geometry") ---

using Locations = std::vector<osmium::Location>;
using WayLocations = std::unordered_map<osmium::object_id_type, Locations>;

constexpr double kStationToTrackMetres = 150;  // bus stops beside the road, platforms beside the track
constexpr double kSimplifyMetres = 3;          // Douglas-Peucker tolerance of an edge's geometry
constexpr double kMaxDetour = 4;               // track between two stations at most this times the
constexpr double kMaxDetourMetres = 2'000;     // straight distance plus this, else the match is wrong
constexpr std::size_t kNamedInProblem = 3;     // gaps or edges a problem names

// Pass 2 (beside StopCollector): the located node positions of the wanted track ways.
class TrackCollector : public osmium::handler::Handler {
 public:
  TrackCollector(const std::unordered_set<osmium::object_id_type>& wanted, TrackBudget& budget)
      : wanted_(wanted), budget_(budget) {}

  void way(const osmium::Way& way) {
    if (!wanted_.count(way.id())) return;
    Locations points;
    for (const auto& node : way.nodes())
      if (node.location().valid() && (points.empty() || points.back() != node.location()))
        points.push_back(node.location());
    budget_.add(points.size());
    if (points.size() < 2) return;
    if (const char* name = well_formed_tags(way.tags()) ? tag_value(way.tags(), "name") : nullptr; name && *name)
      names.emplace(way.id(), name);
    ways.emplace(way.id(), std::move(points));
  }

  WayLocations ways;
  std::unordered_map<osmium::object_id_type, std::string> names;  // of the track ways with one

 private:
  const std::unordered_set<osmium::object_id_type>& wanted_;
  TrackBudget& budget_;
};

using Ways = std::vector<const Locations*>;

bool is_closed(const Locations& w) { return w.size() >= 3 && w.front() == w.back(); }

// Where `loc` is among the distinct nodes of closed way `w` (its last node, the first again, not counted).
std::optional<std::size_t> index_in_loop(const Locations& w, osmium::Location loc) {
  for (std::size_t i = 0; i + 1 < w.size(); ++i)
    if (w[i] == loc) return i;
  return std::nullopt;
}

// `loc` is an end of w, or any node of a closed w.
bool touches(const Locations& w, osmium::Location loc) {
  return w.front() == loc || w.back() == loc || (is_closed(w) && index_in_loop(w, loc));
}

bool touches_any(const Ways& ways, osmium::Location loc) {
  return std::any_of(ways.begin(), ways.end(), [&](const Locations* w) { return touches(*w, loc); });
}

// Appends the nodes of closed way `w` after index k, in its direction (a roundabout is one-way as
// drawn), up to the first node where one of `exits` starts or ends; the whole loop back to k if
// none does (a later way may then leave from any node of it: TrackAssembler::go_back).
void append_loop(Locations& chain, const Locations& w, std::size_t k, const Ways& exits) {
  const std::size_t n = w.size() - 1;  // distinct nodes
  for (std::size_t step = 1; step <= n; ++step) {
    const auto loc = w[(k + step) % n];
    chain.push_back(loc);
    if (std::any_of(exits.begin(), exits.end(),
                    [&](const Locations* e) { return e->front() == loc || e->back() == loc; }))
      return;
  }
}

// Appends `w` where it meets the chain's end: as drawn, reversed, or (a closed way) from the
// node it shares round to an exit. False when it does not meet the chain's end.
bool append_way(Locations& chain, const Locations& w, const Ways& exits) {
  const auto end = chain.back();
  if (is_closed(w)) {
    const auto k = index_in_loop(w, end);
    if (k) append_loop(chain, w, *k, exits);
    return k.has_value();
  }
  if (w.front() == end)
    chain.insert(chain.end(), w.begin() + 1, w.end());
  else if (w.back() == end)
    chain.insert(chain.end(), w.rbegin() + 1, w.rend());
  else
    return false;
  return true;
}

// The first way of a piece of track, turned to run into the ways listed after it (`ahead`):
// reversed when its first node meets one of them and its last does not; a closed way round to
// the node where one of them leaves it; else as drawn (reversed for role "backward": the route
// runs against the way).
Locations start_piece(const Locations& w, const std::string& role, const Ways& ahead) {
  if (is_closed(w)) {
    const std::size_t n = w.size() - 1;
    for (const auto* next : ahead)
      for (const auto loc : {next->front(), next->back()})
        if (const auto k = index_in_loop(w, loc)) {
          Locations out{w[(*k + 1) % n]};
          append_loop(out, w, (*k + 1) % n, {next});
          return out;
        }
    return w;
  }
  for (const auto* next : ahead) {
    const bool last = touches(*next, w.back()), first = touches(*next, w.front());
    if (first != last) return first ? Locations(w.rbegin(), w.rend()) : w;
  }
  return role == "backward" ? Locations(w.rbegin(), w.rend()) : w;
}

struct TrackAssembly {
  std::vector<Locations> pieces;                                                // the track, broken at the gaps
  std::size_t repaired = 0;                                                     // breaks in the member order repaired
  std::vector<std::pair<osmium::object_id_type, osmium::object_id_type>> gaps;  // (way before, way after)
  std::vector<osmium::object_id_type> skipped;  // ways meeting neither the track before nor after them
  std::vector<std::pair<osmium::object_id_type, osmium::object_id_type>> bridged;  // short gaps drawn straight
  std::size_t missing = 0;                                                         // member ways not in the extract
};

constexpr std::size_t kWindow = 4;       // the next ways tried at the chain's end: 3 may be out of order
constexpr double kRewindMetres = 300;    // a chain's excursion this long is dropped, a longer one run back
constexpr double kReturnMetres = 5'000;  // how far back along the chain a way may meet it
constexpr double kBridgeMetres = 100;    // a gap this short is drawn straight (a junction or roundabout way left out)

// A route's track from its way members (the header's "Edge geometry"): at each step, of the next
// kWindow unused ways in member order, the first that continues the chain is appended; where
// none does, in turn: the piece's only way was turned the wrong way; a way meets a node of the
// chain at most kReturnMetres back: up to kRewindMetres back (the route left a way at a junction
// inside it, or went only part way round a roundabout listed whole) the chain is cut back to
// that node, farther back (a branch the route runs up and back, listed once) the chain runs back
// along itself to that node; the chain's end is inside a way (the route joins it at a junction
// inside it) and the ways after it tell which way to go. A way nothing meets is skipped when
// ways listed after it were already taken (listed by mistake); else, where one of the window's
// ways ends within kBridgeMetres of the chain's end, the gap is bridged straight (counted and
// reported); else the track breaks there (a gap). Each step takes one way for good, so it ends.
class TrackAssembler {
 public:
  TrackAssembler(const std::vector<TrackMember>& members, const WayLocations& ways, TrackBudget& budget)
      : members_(members), budget_(budget), used_(members.size(), false) {
    for (const auto& m : members) {
      const auto it = ways.find(m.way);
      list_.push_back(it == ways.end() ? nullptr : &it->second);
      if (!list_.back()) ++out_.missing;
    }
  }

  TrackAssembly run() && {
    for (auto window = next_ways(); !window.empty(); window = next_ways()) {
      const auto first = window.front();
      if (chain_.empty())
        start(first, ways_after(window, first));
      else if (!attach(window))
        at_break(window);
      if (chain_.size() > counted_) budget_.add(chain_.size() - counted_);
      counted_ = chain_.size();
    }
    end_piece();
    return std::move(out_);
  }

 private:
  // No way of the window continues the chain at its end: a repair, a way left out, a bridge or a gap.
  void at_break(const std::vector<std::size_t>& window) {
    for (const auto i : window) budget_.add(list_[i]->size());  // the repairs go over each a few times
    const auto first = window.front();
    if (repair(window)) return;
    if (taken_beyond_ > first) {
      used_[first] = true;
      out_.skipped.push_back(members_[first].way);
    } else if (!bridge(window)) {
      out_.gaps.push_back({last_way_, members_[first].way});
      end_piece();
    }
  }
  // The first kWindow unused ways in the extract, in member order.
  std::vector<std::size_t> next_ways() {
    while (next_ < list_.size() && (used_[next_] || !list_[next_])) ++next_;
    std::vector<std::size_t> out;
    for (std::size_t i = next_; i < list_.size() && out.size() < kWindow; ++i)
      if (!used_[i] && list_[i]) out.push_back(i);
    return out;
  }
  Ways ways_after(const std::vector<std::size_t>& window, std::size_t except) const {
    Ways out;
    for (const auto i : window)
      if (i != except) out.push_back(list_[i]);
    return out;
  }
  void take(std::size_t i, bool in_order) {
    used_[i] = true;
    last_way_ = members_[i].way;
    taken_beyond_ = std::max(taken_beyond_, i);
    if (!in_order) ++out_.repaired;
  }
  void start(std::size_t i, const Ways& ahead) {
    end_piece();
    chain_ = start_piece(*list_[i], members_[i].role, ahead);
    marks_ = {0};
    take(i, true);
  }
  void end_piece() {
    if (chain_.size() >= 2) out_.pieces.push_back(std::move(chain_));
    chain_.clear();
    marks_.clear();
    counted_ = 0;
  }
  bool append(std::size_t i, const std::vector<std::size_t>& window) {
    const auto size = chain_.size();
    if (!append_way(chain_, *list_[i], ways_after(window, i))) return false;
    marks_.push_back(size);
    return true;
  }
  // The first of the window continuing the chain at its end.
  bool attach(const std::vector<std::size_t>& window) {
    for (const auto i : window)
      if (append(i, window)) {
        take(i, i == window.front());
        return true;
      }
    return false;
  }
  bool repair(const std::vector<std::size_t>& window) {
    // The piece's only way turned the wrong way.
    if (marks_.size() == 1)
      for (const auto i : window)
        if (touches(*list_[i], chain_.front())) {
          std::reverse(chain_.begin(), chain_.end());
          if (append(i, window)) {
            take(i, false);
            return true;
          }
          std::reverse(chain_.begin(), chain_.end());
        }
    for (const auto i : window)
      if (go_back(i, window) || enter_inside(i, window)) {
        take(i, false);
        return true;
      }
    return false;
  }
  // Way i meets the chain at most kReturnMetres back from its end (the latest such node): the
  // chain is cut back to it (up to kRewindMetres) or runs back to it, and way i is appended.
  bool go_back(std::size_t i, const std::vector<std::size_t>& window) {
    const auto& w = *list_[i];
    std::unordered_set<std::uint64_t> meets;  // the nodes of w the chain may meet: its ends, any of a closed way
    for (const auto& loc : is_closed(w) ? w : Locations{w.front(), w.back()}) meets.insert(key_of(loc));
    double back = 0;
    std::size_t scanned = 0;
    for (std::size_t p = chain_.size() - 1; p-- > 0 && back <= kReturnMetres; ++scanned) {
      const auto [x, y] = metres_from({chain_[p + 1].lon(), chain_[p + 1].lat()}, {chain_[p].lon(), chain_[p].lat()});
      back += std::hypot(x, y);
      if (back > kReturnMetres || !meets.count(key_of(chain_[p]))) continue;
      budget_.add(scanned);
      if (back <= kRewindMetres) {
        chain_.resize(p + 1);
        while (marks_.size() > 1 && marks_.back() > p) marks_.pop_back();
      } else {
        marks_.push_back(chain_.size());
        for (std::size_t q = chain_.size() - 1; q-- > p;) {
          const auto loc = chain_[q];  // not a reference into the vector it grows
          chain_.push_back(loc);
        }
      }
      return append(i, window);
    }
    budget_.add(scanned);
    return false;
  }
  static std::uint64_t key_of(osmium::Location loc) {
    return std::uint64_t{static_cast<std::uint32_t>(loc.x())} << 32 | static_cast<std::uint32_t>(loc.y());
  }
  // The first way of the window with an end within kBridgeMetres of the chain's end, from that end.
  bool bridge(const std::vector<std::size_t>& window) {
    const auto end = chain_.back();
    const auto metres_to = [&](osmium::Location loc) {
      const auto [x, y] = metres_from({end.lon(), end.lat()}, {loc.lon(), loc.lat()});
      return std::hypot(x, y);
    };
    for (const auto i : window) {
      const auto& w = *list_[i];
      if (is_closed(w)) continue;
      const double to_first = metres_to(w.front()), to_last = metres_to(w.back());
      if (std::min(to_first, to_last) > kBridgeMetres) continue;
      out_.bridged.push_back({last_way_, members_[i].way});
      marks_.push_back(chain_.size());
      if (to_first <= to_last)
        chain_.insert(chain_.end(), w.begin(), w.end());
      else
        chain_.insert(chain_.end(), w.rbegin(), w.rend());
      take(i, false);
      return true;
    }
    return false;
  }
  // The chain's end is inside way i: on along it towards the end the ways after it meet.
  bool enter_inside(std::size_t i, const std::vector<std::size_t>& window) {
    const auto& w = *list_[i];
    if (is_closed(w)) return false;
    const auto k = std::find(w.begin() + 1, w.end() - 1, chain_.back());
    if (k == w.end() - 1) return false;
    const auto after = ways_after(window, i);
    const bool to_last = touches_any(after, w.back()), to_first = touches_any(after, w.front());
    if (to_last == to_first) return false;
    marks_.push_back(chain_.size());
    if (to_last)
      chain_.insert(chain_.end(), k + 1, w.end());
    else
      chain_.insert(chain_.end(), std::make_reverse_iterator(k), w.rend());
    return true;
  }

  const std::vector<TrackMember>& members_;
  TrackBudget& budget_;
  std::vector<const Locations*> list_;  // each member's way, null when not in the extract
  std::vector<bool> used_;
  std::size_t next_ = 0;          // no unused way before this member
  std::size_t taken_beyond_ = 0;  // the last member taken so far
  TrackAssembly out_;
  Locations chain_;                 // the piece being built
  std::vector<std::size_t> marks_;  // where each of its ways starts in the chain
  std::size_t counted_ = 0;         // chain positions counted against the budget
  osmium::object_id_type last_way_ = 0;
};

// A piece of track in lon/lat and in metres of the route's frame (metres_from its origin).
struct Metres {
  double x = 0, y = 0;
};
struct Piece {
  std::vector<geo::LonLat> ll;
  std::vector<Metres> xy;
};

Metres metres(geo::LonLat origin, geo::LonLat p) {
  const auto [x, y] = metres_from(origin, p);
  return {x, y};
}

// A point on the track: its piece, segment (from point `segment` to the next) and fraction along it.
struct TrackPos {
  std::size_t piece = 0, segment = 0;
  double t = 0;
};

// The fraction t >= t0 along segment a-b nearest to p, and the distance from p to it.
std::pair<double, double> nearest_on(Metres p, Metres a, Metres b, double t0) {
  const double dx = b.x - a.x, dy = b.y - a.y, length2 = dx * dx + dy * dy;
  const double t = length2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / length2, t0, 1.0) : t0;
  return {t, std::hypot(a.x + t * dx - p.x, a.y + t * dy - p.y)};
}

// The track position nearest to p at or after `from`, within the first stretch of track after
// `from` that comes within kStationToTrackMetres of p (a later pass of the same street is
// another station's); none when the rest of the track never comes that close.
// Counts the segments looked at in `budget`.
std::optional<TrackPos> locate(const std::vector<Piece>& pieces, Metres p, TrackPos from, TrackBudget& budget) {
  std::optional<TrackPos> best;
  double best_distance = kStationToTrackMetres;
  std::size_t scanned = 0;
  for (std::size_t k = from.piece; k < pieces.size(); ++k) {
    const auto& xy = pieces[k].xy;
    for (std::size_t s = k == from.piece ? from.segment : 0; s + 1 < xy.size(); ++s, ++scanned) {
      const bool first = k == from.piece && s == from.segment;
      const auto [t, distance] = nearest_on(p, xy[s], xy[s + 1], first ? from.t : 0.0);
      if (distance <= best_distance) {
        best = TrackPos{k, s, t};
        best_distance = distance;
      } else if (best && distance > kStationToTrackMetres) {
        break;  // the stretch ended
      }
    }
    if (best) break;  // a stretch ends with its piece
  }
  budget.add(scanned);
  return best;
}

// Douglas-Peucker over `points` (lon/lat with their metres), keeping both ends. Counts the
// distances measured in `budget` (quadratic at worst).
std::vector<geo::LonLat> simplify(const std::vector<std::pair<geo::LonLat, Metres>>& points, double tolerance,
                                  TrackBudget& budget) {
  std::vector<bool> keep(points.size(), false);
  keep.front() = keep.back() = true;
  std::vector<std::pair<std::size_t, std::size_t>> spans{{0, points.size() - 1}};
  while (!spans.empty()) {
    const auto [i, j] = spans.back();
    spans.pop_back();
    std::size_t farthest = i;
    double distance = tolerance;
    budget.add(j - i);
    for (std::size_t k = i + 1; k < j; ++k)
      if (const double d = nearest_on(points[k].second, points[i].second, points[j].second, 0).second; d > distance) {
        distance = d;
        farthest = k;
      }
    if (farthest == i) continue;
    keep[farthest] = true;
    spans.push_back({i, farthest});
    spans.push_back({farthest, j});
  }
  std::vector<geo::LonLat> out;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (keep[k]) out.push_back(points[k].first);
  return out;
}

// Why a pair of consecutive stations got no track.
enum class NoTrack { none, first_off_track, second_off_track, gap, detour, turn };

struct Cut {
  std::vector<geo::LonLat> geometry;  // from the first station to the second, when why is none
  NoTrack why = NoTrack::none;
};

// The route's track between consecutive stations: each station placed on the track (locate),
// each pair's track cut out between their places, with the stations' positions at its ends.
class TrackCutter {
 public:
  TrackCutter(const std::vector<Locations>& pieces, bool reversed, TrackBudget& budget) : budget_(budget) {
    for (const auto& locations : pieces) {
      Piece piece;
      for (const auto& loc : locations) piece.ll.push_back({loc.lon(), loc.lat()});
      if (reversed) std::reverse(piece.ll.begin(), piece.ll.end());
      pieces_.push_back(std::move(piece));
    }
    if (reversed) std::reverse(pieces_.begin(), pieces_.end());
    if (pieces_.empty()) return;
    origin_ = pieces_.front().ll.front();
    // A loop (the track ends where it starts) may start anywhere among the stops: it is gone
    // round twice, so the stations after its start are found on the second round.
    const auto [x, y] = metres_from(origin_, pieces_.back().ll.back());
    if (std::hypot(x, y) <= kBridgeMetres) {
      const auto once = pieces_;
      pieces_.back().ll.insert(pieces_.back().ll.end(), once.front().ll.begin(), once.front().ll.end());
      pieces_.insert(pieces_.end(), once.begin() + 1, once.end());
    }
    for (auto& piece : pieces_)
      for (const auto& p : piece.ll) piece.xy.push_back(metres(origin_, p));
  }

  // The cuts between consecutive `stations`, placed on the track in order.
  std::vector<Cut> cut(const std::vector<geo::LonLat>& stations) const {
    std::vector<std::optional<TrackPos>> on_track;
    TrackPos from;
    for (const auto& s : stations) {
      on_track.push_back(pieces_.empty() ? std::nullopt : locate(pieces_, metres(origin_, s), from, budget_));
      if (on_track.back()) from = *on_track.back();
    }
    std::vector<Cut> out;
    for (std::size_t i = 0; i + 1 < stations.size(); ++i) {
      if (!on_track[i])
        out.push_back({{}, NoTrack::first_off_track});
      else if (!on_track[i + 1])
        out.push_back({{}, NoTrack::second_off_track});
      else if (on_track[i]->piece != on_track[i + 1]->piece)
        out.push_back({{}, NoTrack::gap});
      else
        out.push_back(between(*on_track[i], *on_track[i + 1], stations[i], stations[i + 1]));
    }
    return out;
  }

 private:
  // The track from a to b (a not after b, on one piece) with the stations at its ends, simplified.
  Cut between(TrackPos a, TrackPos b, geo::LonLat first, geo::LonLat second) const {
    const auto& piece = pieces_[a.piece];
    std::vector<std::pair<geo::LonLat, Metres>> points;
    const auto add = [&](geo::LonLat ll, Metres xy) {
      if (points.empty() || std::hypot(xy.x - points.back().second.x, xy.y - points.back().second.y) > 0.01)
        points.push_back({ll, xy});
    };
    const auto start = metres(origin_, first), end = metres(origin_, second);
    add(first, start);
    add(at(piece, a).first, at(piece, a).second);
    for (std::size_t k = a.segment + 1; k <= b.segment; ++k) add(piece.ll[k], piece.xy[k]);
    add(at(piece, b).first, at(piece, b).second);
    add(second, end);
    if (points.size() < 2) return {{first, second}, NoTrack::none};
    double length = 0;
    for (std::size_t k = 1; k < points.size(); ++k)
      length += std::hypot(points[k].second.x - points[k - 1].second.x, points[k].second.y - points[k - 1].second.y);
    if (length > kMaxDetour * std::hypot(end.x - start.x, end.y - start.y) + kMaxDetourMetres)
      return {{}, NoTrack::detour};
    return {simplify(points, kSimplifyMetres, budget_), NoTrack::none};
  }
  static std::pair<geo::LonLat, Metres> at(const Piece& piece, TrackPos pos) {
    const auto s = pos.segment;
    const double t = pos.t;
    const auto& a = piece.ll[s];
    const auto& b = piece.ll[s + 1];
    return {{a.lon + t * (b.lon - a.lon), a.lat + t * (b.lat - a.lat)},
            {piece.xy[s].x + t * (piece.xy[s + 1].x - piece.xy[s].x),
             piece.xy[s].y + t * (piece.xy[s + 1].y - piece.xy[s].y)}};
  }

  TrackBudget& budget_;  // counts the searches (locate, simplify)
  geo::LonLat origin_;
  std::vector<Piece> pieces_;
};

std::size_t cut_count(const std::vector<Cut>& cuts) {
  return static_cast<std::size_t>(
      std::count_if(cuts.begin(), cuts.end(), [](const Cut& c) { return c.why == NoTrack::none; }));
}

// The cuts between consecutive stations: those served on the way out (kForward) along the track as
// assembled, those served on the way back (kBackward) along it reversed; or the other way round
// where that cuts more pairs (a route whose ways are listed against the order of its stops). A
// pair of the way out and the way back (the route turns between them) gets none.
std::vector<Cut> cut_track(const std::vector<Locations>& pieces, const std::vector<geo::LonLat>& stations,
                           const std::vector<unsigned char>& directions, TrackBudget& budget) {
  // A station served both ways (an end, where the route turns) is on the way out up to the turn,
  // on the way back from it: the route lists the way out first.
  const std::size_t n = stations.size();
  std::size_t last_out = n,
              first_back = n;  // the last station served only on the way out; the first only on the way back
  for (std::size_t i = 0; i < n; ++i) {
    if (directions[i] == kForward) last_out = i;
    if (directions[i] == kBackward && first_back == n) first_back = i;
  }
  std::vector<std::size_t> out, back;  // indices of the stations served each way
  for (std::size_t i = 0; i < n; ++i) {
    const bool both = directions[i] == kBothWays;
    if ((directions[i] & kForward) && (!both || last_out == n || i <= last_out + 1)) out.push_back(i);
    if ((directions[i] & kBackward) && (!both || first_back == n || i + 1 >= first_back)) back.push_back(i);
  }
  const auto positions = [&](const std::vector<std::size_t>& indices) {
    std::vector<geo::LonLat> p;
    for (const auto i : indices) p.push_back(stations[i]);
    return p;
  };
  const TrackCutter as_assembled(pieces, false, budget), reversed(pieces, true, budget);
  std::vector<Cut> best;
  for (const bool flip : {false, true}) {
    const auto out_cuts = (flip ? reversed : as_assembled).cut(positions(out));
    const auto back_cuts = (flip ? as_assembled : reversed).cut(positions(back));
    std::vector<Cut> cuts(stations.size() - 1, Cut{{}, NoTrack::turn});
    // Pairs of consecutive stations in `indices` are consecutive stations of the route.
    const auto fill = [&](const std::vector<std::size_t>& indices, const std::vector<Cut>& from) {
      for (std::size_t k = 0; k < from.size(); ++k)
        if (cuts[indices[k]].why != NoTrack::none && indices[k + 1] == indices[k] + 1) cuts[indices[k]] = from[k];
    };
    fill(out, out_cuts);
    fill(back, back_cuts);
    if (best.empty() || cut_count(cuts) > cut_count(best)) best = std::move(cuts);
    if (cut_count(best) == best.size()) break;
  }
  return best;
}

void report(OsmTransitStats& stats, osmium::object_id_type relation, std::string message) {
  if (stats.problems.size() < kMaxOsmRouteProblems)
    stats.problems.push_back({relation, std::move(message)});
  else
    ++stats.problems_left_off;
}

// "a, b, c, ..." of the first kNamedInProblem of `total` items.
std::string named(const std::vector<std::string>& items, std::size_t total) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return total > items.size() ? out + ", ..." : out;
}

// "1 gap", "2 gaps".
std::string count_of(std::size_t n, const std::string& what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

// Reports what a route's track assembly could not do: ways missing, gaps left.
void report_assembly(const Route& route, const TrackAssembly& track, OsmTransitStats& stats) {
  const auto label = route_label(route);
  if (route.track.empty())
    report(stats, route.id, label + ": no track ways, its edges are straight");
  else if (track.missing > 0)
    report(stats, route.id,
           label + ": " + std::to_string(track.missing) + " of " + std::to_string(route.track.size()) +
               " track ways not in the extract");
  if (!track.skipped.empty()) {
    std::vector<std::string> ways;
    for (std::size_t w = 0; w < track.skipped.size() && w < kNamedInProblem; ++w)
      ways.push_back(std::to_string(track.skipped[w]));
    report(stats, route.id,
           label + ": " + count_of(track.skipped.size(), "track way") +
               " meeting neither the ways before nor after, left out: " + named(ways, track.skipped.size()));
  }
  const auto between = [](const auto& pairs) {
    std::vector<std::string> out;
    for (std::size_t g = 0; g < pairs.size() && g < kNamedInProblem; ++g)
      out.push_back("between ways " + std::to_string(pairs[g].first) + " and " + std::to_string(pairs[g].second));
    return named(out, pairs.size());
  };
  if (!track.bridged.empty())
    report(stats, route.id,
           label + ": " + count_of(track.bridged.size(), "gap") + " under " +
               std::to_string(static_cast<int>(kBridgeMetres)) + " m in the track drawn straight, " +
               between(track.bridged));
  if (track.gaps.empty()) return;
  report(stats, route.id, label + ": " + count_of(track.gaps.size(), "gap") + " in the track, " + between(track.gaps));
}

// A route's stations as nodes of the network: their indices, positions and names.
struct RouteStations {
  std::vector<std::uint32_t> nodes;
  std::vector<geo::LonLat> positions;
  std::vector<std::string> names;
  std::vector<unsigned char> directions;  // Direction bits
};

// Gives the route's edges the geometry of its track where no earlier route gave them one (the
// pairs of nodes with track go to `with_track`); counts and reports what it could not do.
void add_track(const Route& route, const RouteStations& stations, const WayLocations& ways, MetroBuilder& builder,
               TrackBudget& budget, std::set<std::pair<std::uint32_t, std::uint32_t>>& with_track,
               OsmTransitStats& stats, const std::string& where) {
  const auto track = TrackAssembler(route.track, ways, budget).run();
  stats.gaps_repaired += track.repaired;
  stats.gaps += track.gaps.size();
  stats.missing_track_members += track.missing;
  stats.skipped_track_members += track.skipped.size();
  report_assembly(route, track, stats);
  if (track.pieces.empty()) return;
  ++stats.routes_with_track;
  auto cuts = cut_track(track.pieces, stations.positions, stations.directions, budget);
  std::vector<std::string> straight;
  std::size_t straight_count = 0;
  const auto& names = stations.names;
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    const auto a = stations.nodes[i], b = stations.nodes[i + 1];
    const auto why = cuts[i].why;
    if (why == NoTrack::none) {
      builder.replace_straight_geometry(a, b, std::move(cuts[i].geometry), where);
      with_track.insert(std::minmax(a, b));
      continue;
    }
    if (++straight_count > kNamedInProblem) continue;
    const std::string reason = why == NoTrack::gap      ? "a gap in the track"
                               : why == NoTrack::detour ? "the track runs far around"
                               : why == NoTrack::turn
                                   ? "the route turns back between them"
                                   : names[why == NoTrack::first_off_track ? i : i + 1] + " not within " +
                                         std::to_string(static_cast<int>(kStationToTrackMetres)) + " m of the track";
    straight.push_back(names[i] + " - " + names[i + 1] + " (" + reason + ")");
  }
  if (straight_count > 0)
    report(stats, route.id,
           route_label(route) + ": " + std::to_string(straight_count) + " of " +
               count_of(stations.nodes.size() - 1, "edge") + " straight: " + named(straight, straight_count));
}

// The name of the named track way (a bus route's street) nearest to `p` within
// kStreetNameMetres, else "". Brute force over the routes' ways: run once per station that has
// no name of its own (two in Liechtenstein), over at most max_osm_track_points positions.
std::string nearest_street_name(geo::LonLat p, const WayLocations& ways,
                                const std::unordered_map<osmium::object_id_type, std::string>& names) {
  double best = kStreetNameMetres;
  const std::string* found = nullptr;
  for (const auto& [id, name] : names) {
    const auto& points = ways.at(id);
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
      const auto [ax, ay] = metres_from(p, {points[i].lon(), points[i].lat()});
      const auto [bx, by] = metres_from(p, {points[i + 1].lon(), points[i + 1].lat()});
      const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
      const double t = len2 > 0 ? std::clamp(-(ax * dx + ay * dy) / len2, 0.0, 1.0) : 0.0;
      if (const double d = std::hypot(ax + t * dx, ay + t * dy); d < best) {
        best = d;
        found = &name;
      }
    }
  }
  return found ? *found : "";
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
    TrackBudget budget(limits, source);
    read_relations(input.file(), pass, limits, source, stats, budget);
    // Modes asked: the routes of other modes are dropped now. None asked: every route is read on,
    // and the modes are chosen from the routes with two stops in the extract (a train route whose
    // stations all lie outside, passing through, does not make Monaco a train map).
    const auto keep_modes = [&](const std::vector<std::string>& modes) {
      std::erase_if(pass.routes,
                    [&](const Route& r) { return std::find(modes.begin(), modes.end(), r.mode) == modes.end(); });
    };
    if (!asked.empty()) keep_modes(asked);

    std::set<ObjectKey> candidates;  // stop, platform and other node members
    std::unordered_set<osmium::object_id_type> track_ways;
    for (const auto& route : pass.routes) {
      for (const auto* keys : {&route.stops, &route.platforms, &route.other_nodes})
        candidates.insert(keys->begin(), keys->end());
      for (const auto& member : route.track) track_ways.insert(member.way);
    }
    StopCollector collector(candidates, limits, source);
    TrackCollector tracks(track_ways, budget);
    {
      osmium::io::Reader reader(input.file(), osmium::osm_entity_bits::node | osmium::osm_entity_bits::way);
      LocationIndex index;
      LocationHandler locations(index);
      locations.ignore_errors();
      while (osmium::memory::Buffer buffer = reader.read()) {
        util::check_stop();
        osmium::apply(buffer, locations, collector, tracks);
      }
      reader.close();
    }
    const auto located = [&](const std::vector<ObjectKey>& keys) {
      return std::count_if(keys.begin(), keys.end(), [&](const ObjectKey& k) { return collector.stops.count(k) != 0; });
    };
    if (asked.empty()) {
      std::vector<std::string> present;
      for (const auto& r : pass.routes)
        if ((located(r.stops) >= 2 || located(r.platforms) >= 2 || located(r.other_nodes) >= 2) &&
            std::find(present.begin(), present.end(), r.mode) == present.end())
          present.push_back(r.mode);
      stats.modes = default_transit_modes(present);
      keep_modes(stats.modes);
    } else {
      stats.modes = asked;
    }
    stats.routes = pass.routes.size();

    std::set<ObjectKey> wanted;  // stops and platforms of the routes kept
    for (const auto& route : pass.routes) {
      wanted.insert(route.stops.begin(), route.stops.end());
      wanted.insert(route.platforms.begin(), route.platforms.end());
    }
    stats.missing_stop_members =
        wanted.size() - static_cast<std::size_t>(std::count_if(wanted.begin(), wanted.end(), [&](const ObjectKey& k) {
          return collector.stops.count(k) != 0;
        }));
    // Older routes list their stops as plain node members (role ""): those are stops of a route
    // with fewer than two stop positions and two platforms in the extract, other plain nodes none.
    std::set<ObjectKey> plain_stops;
    for (const auto& route : pass.routes)
      if (located(route.stops) < 2 && located(route.platforms) < 2)
        plain_stops.insert(route.other_nodes.begin(), route.other_nodes.end());
    std::erase_if(collector.stops,
                  [&](const auto& stop) { return !wanted.count(stop.first) && !plain_stops.count(stop.first); });
    stats.stops = collector.stops.size();

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
      if (into) {
        add_to(*into, key, stop);
        continue;
      }
      // Named after its street; the stop across the street, named so before, is the same station.
      auto street = nearest_street_name(stop.pos, tracks.ways, tracks.names);
      if (auto it = stations_by_name.find(ascii_lower(street)); !street.empty() && it != stations_by_name.end())
        for (auto s : it->second)
          if (!into && geo::geodesic_distance_m(stations[s].first, stop.pos) <= kSameStationMetres) into = s;
      add_to(into ? *into : new_station(key, stop, std::move(street)), key, stop);
    }

    // Lines and their edges.
    MetroBuilder builder(limits);
    std::unordered_map<osmium::object_id_type, osmium::object_id_type> master_of;
    for (const auto& [id, master] : pass.masters)
      for (auto route : master.routes) master_of[route] = id;
    std::vector<std::optional<std::uint32_t>> node_of_station(stations.size());
    const auto name_of = [&](std::size_t s) {
      return stations[s].name.empty() ? "Stop " + stations[s].id.substr(2) : stations[s].name;
    };
    const auto node_of = [&](std::size_t s) {
      if (!node_of_station[s]) {
        auto& st = stations[s];
        const geo::LonLat pos{st.lon / static_cast<double>(st.stops), st.lat / static_cast<double>(st.stops)};
        node_of_station[s] = builder.add_node({st.id, st.id, name_of(s), pos}, source + " station " + st.id);
        ++stats.stations;
      }
      return *node_of_station[s];
    };
    std::set<std::pair<std::uint32_t, std::uint32_t>> with_track;  // node pairs whose edge has track geometry
    // Routes without a master: one line per mode and ref (the two directions of a route are
    // often two relations with no master over them), else one per route.
    std::map<std::pair<std::string, std::string>, osmium::object_id_type> line_of_ref;
    std::set<osmium::object_id_type> masters_used;
    for (const auto& route : pass.routes) {
      // The stations in the order of the stop positions, or of the platforms where fewer than
      // two stop positions are in the extract (mappers often list all stops, then all platforms).
      const auto sequence_of = [&](const std::vector<ObjectKey>& keys) {
        std::vector<std::pair<std::size_t, unsigned char>> sequence;  // (station, direction)
        for (const auto& key : keys) {
          const auto it = station_of.find(key);
          if (it == station_of.end()) continue;
          if (!sequence.empty() && sequence.back().first == it->second)
            sequence.back().second |= route.direction(key);
          else
            sequence.push_back({it->second, route.direction(key)});
        }
        return sequence;
      };
      auto sequence = sequence_of(route.stops);
      if (sequence.size() < 2) sequence = sequence_of(route.platforms);
      if (sequence.size() < 2) sequence = sequence_of(route.other_nodes);
      if (sequence.size() < 2) {
        ++stats.routes_without_stops;
        report(stats, route.id, route_label(route) + ": fewer than two stops in the extract, not used");
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
      RouteStations route_stations;
      for (const auto& [s, direction] : sequence) {
        route_stations.nodes.push_back(node_of(s));
        route_stations.positions.push_back(builder.pos(route_stations.nodes.back()));
        route_stations.names.push_back(name_of(s));
        route_stations.directions.push_back(direction);
      }
      for (std::size_t i = 0; i + 1 < sequence.size(); ++i)
        builder.connect(route_stations.nodes[i], route_stations.nodes[i + 1], l, where);
      add_track(route, route_stations, tracks.ways, builder, budget, with_track, stats, where);
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
    stats.track_points = budget.used();
    for (const auto& e : net.edges)
      ++(with_track.count(std::minmax(e.from, e.to)) ? stats.track_edges : stats.straight_edges);
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
