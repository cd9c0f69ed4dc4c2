#include "load/metro_gtfs.hpp"

#include "load/csv.hpp"
#include "load/csv_stream.hpp"
#include "load/file.hpp"
#include "load/load_error.hpp"
#include "load/metro_builder.hpp"
#include "load/metro_osm.hpp"
#include "load/strings.hpp"
#include "util/stop.hpp"

#include <zip.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <tuple>
#include <unordered_map>

namespace tourmap::load {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
// A station farther than this from its trip's shape: the shape is not of this pattern (or the
// station is misplaced); its edges are drawn straight.
constexpr double kMaxShapeOffsetMetres = 300;
// Along a shape, a station takes the first place where the shape comes closest to it (a local
// minimum of the distance) within this much of the closest of all, so an out-and-back shape on
// one street gives the outbound stations the outbound leg.
constexpr double kShapeSlackMetres = 30;

const std::vector<std::string> kModes = {"subway", "light_rail", "tram",  "train",      "monorail",   "funicular",
                                         "bus",    "trolleybus", "ferry", "cable_tram", "aerial_lift", "coach"};

// An id or value quoted for a message, clipped: a field may be a megabyte long.
std::string quote_id(std::string_view text) {
  constexpr std::size_t kMax = 64;
  return "'" + std::string(text.substr(0, kMax)) + (text.size() > kMax ? "...'" : "'");
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

// "#1F77B4" or "1f77b4" -> "1f77b4"; anything else -> "".
std::string colour_of(std::string_view value) {
  value = trim(value);
  if (value.size() == 7 && value[0] == '#') value.remove_prefix(1);
  if (value.size() != 6 || !std::all_of(value.begin(), value.end(), [](unsigned char c) { return std::isxdigit(c); }))
    return "";
  return ascii_lower(std::string(value));
}

long parse_integer(std::string_view field, const std::string& where, std::string_view column) {
  const auto s = trim(field);
  long value = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (s.empty() || ec != std::errc() || ptr != s.data() + s.size())
    throw LoadError(where, std::string(column) + " is not an integer: " + quote_id(s));
  return value;
}

// stop_sequence, shape_pt_sequence: non-negative integers.
std::uint32_t parse_sequence(std::string_view field, const std::string& where, std::string_view column) {
  const auto s = trim(field);
  std::uint32_t value = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (s.empty() || ec != std::errc() || ptr != s.data() + s.size())
    throw LoadError(where, std::string(column) + " is not a non-negative integer: " + quote_id(s));
  return value;
}

// A lat/lon pair; throws on a non-number or a position off the globe.
geo::LonLat parse_position(std::string_view lat, std::string_view lon, const std::string& where,
                           std::string_view lat_column, std::string_view lon_column) {
  const geo::LonLat p{parse_number(lon, where, lon_column), parse_number(lat, where, lat_column)};
  if (!geo::is_valid(p))
    throw LoadError(where, "coordinates out of range: " + std::string(lat_column) + " " + std::string(trim(lat)) + ", " +
                               std::string(lon_column) + " " + std::string(trim(lon)));
  return p;
}

// Hash maps keyed by id that are searched with the string_view of a field (no copy per row).
struct StringHash {
  using is_transparent = void;
  std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
};
template <class V>
using IdMap = std::unordered_map<std::string, V, StringHash, std::equal_to<>>;

template <class V>
const V* find_id(const IdMap<V>& map, std::string_view id) {
  const auto it = map.find(id);
  return it == map.end() ? nullptr : &it->second;
}

// --- the feed: a folder or a zip file ---

class FileSource final : public ByteSource {
 public:
  FileSource(const std::string& path, std::string name) : name_(std::move(name)) {
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) throw LoadError(name_, std::string("cannot open: ") + std::strerror(errno));
  }
  ~FileSource() override { std::fclose(file_); }
  FileSource(const FileSource&) = delete;
  FileSource& operator=(const FileSource&) = delete;

  std::size_t read(char* buffer, std::size_t size) override {
    const std::size_t n = std::fread(buffer, 1, size, file_);
    if (n < size && std::ferror(file_)) throw LoadError(name_, "read failed");
    return n;
  }

 private:
  std::FILE* file_ = nullptr;
  std::string name_;
};

// A zip entry, inflated as it is read (zip_fread), never whole in memory.
class ZipEntrySource final : public ByteSource {
 public:
  ZipEntrySource(zip_t* zip, zip_uint64_t index, std::string name) : name_(std::move(name)) {
    file_ = zip_fopen_index(zip, index, 0);
    if (!file_) throw LoadError(name_, std::string("cannot open in the zip file: ") + zip_strerror(zip));
  }
  ~ZipEntrySource() override { zip_fclose(file_); }
  ZipEntrySource(const ZipEntrySource&) = delete;
  ZipEntrySource& operator=(const ZipEntrySource&) = delete;

  std::size_t read(char* buffer, std::size_t size) override {
    const zip_int64_t n = zip_fread(file_, buffer, size);
    if (n < 0) throw LoadError(name_, std::string("cannot inflate: ") + zip_file_strerror(file_));
    return static_cast<std::size_t>(n);
  }

 private:
  zip_file_t* file_ = nullptr;
  std::string name_;
};

// The name of a feed in messages: its file or folder name ("feed.zip", "vienna-gtfs").
std::string feed_name(std::string path) {
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  return file_name(path);
}

class Feed {
 public:
  explicit Feed(const std::string& path) : path_(path), name_(feed_name(path)) {
    if (std::filesystem::is_directory(path)) return;
    if (!std::filesystem::is_regular_file(path)) throw LoadError(path, "no such file or folder");
    int error = 0;
    zip_ = zip_open(path.c_str(), ZIP_RDONLY, &error);
    if (!zip_) {
      zip_error_t e;
      zip_error_init_with_code(&e, error);
      const std::string what = zip_error_strerror(&e);
      zip_error_fini(&e);
      throw LoadError(name_, "not a GTFS zip file or folder (" + what + ")");
    }
  }
  ~Feed() {
    if (zip_) zip_discard(zip_);
  }
  Feed(const Feed&) = delete;
  Feed& operator=(const Feed&) = delete;

  const std::string& name() const { return name_; }

  // The file `name`, or null when the feed has none. A zip's entries may sit in a folder.
  std::unique_ptr<ByteSource> open(const std::string& name) const {
    if (!zip_) {
      const auto file = std::filesystem::path(path_) / name;
      if (!std::filesystem::is_regular_file(file)) return nullptr;
      return std::make_unique<FileSource>(file.string(), name);
    }
    zip_int64_t index = zip_name_locate(zip_, name.c_str(), 0);  // at the top first
    if (index < 0) index = zip_name_locate(zip_, name.c_str(), ZIP_FL_NODIR | ZIP_FL_NOCASE);
    if (index < 0) return nullptr;
    return std::make_unique<ZipEntrySource>(zip_, static_cast<zip_uint64_t>(index), name);
  }
  std::unique_ptr<ByteSource> require(const std::string& name) const {
    auto in = open(name);
    if (!in) throw LoadError(name_, "no " + name);
    return in;
  }

 private:
  std::string path_, name_;
  zip_t* zip_ = nullptr;
};

// --- what the feed holds ---

struct Route {
  std::string id, label, colour, mode;
  bool has_trips = false;
  bool kept = false;  // of the modes read, with a trip
};

struct Trip {
  std::uint32_t route = 0;
  std::uint32_t shape = kNone;
  std::uint32_t pattern = kNone;
  std::uint8_t runs = 0;  // groups of consecutive rows in stop_times.txt seen: 0, 1, 2 (or more)
};

struct Station {
  std::string stop_id, name;
  std::optional<geo::LonLat> pos;    // its own
  double lon = 0, lat = 0;           // sums over its stops (location_type 0) with coordinates
  std::size_t stops = 0;
  double other_lon = 0, other_lat = 0;  // over its entrances, nodes, boarding areas
  std::size_t others = 0;
  std::uint32_t node = kNone;
};

// One stop_times row of a kept trip.
struct Row {
  std::uint32_t sequence, station;
};

struct Pattern {
  std::uint32_t route;
  const std::vector<std::uint32_t>* key;  // route, then the stations (in the smaller direction)
  std::uint32_t shape = kNone;            // of a trip that runs it
  bool shape_reversed = false;            // that trip runs the stations backwards
  std::size_t trips = 0;
};

struct VectorHash {
  std::size_t operator()(const std::vector<std::uint32_t>& v) const {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the words
    for (auto x : v) h = (h ^ x) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

struct Gtfs {
  explicit Gtfs(const ImportLimits& l) : limits(l) {}

  const ImportLimits& limits;
  std::vector<Route> routes;
  IdMap<std::uint32_t> route_index;
  std::vector<Trip> trips;
  IdMap<std::uint32_t> trip_index;
  IdMap<std::uint32_t> shape_index;  // shape ids of trips
  std::vector<Station> stations;
  IdMap<std::uint32_t> station_of_stop;
  std::unordered_map<std::vector<std::uint32_t>, std::uint32_t, VectorHash> pattern_index;
  std::vector<Pattern> patterns;
  std::size_t held = 0;  // stations of the patterns (counted in max_gtfs_buffered_stop_times)
  GtfsStats stats;

  CsvStreamBounds bounds() const {
    return {limits.max_gtfs_file_bytes, "max_gtfs_file_bytes", limits.max_gtfs_rows, "max_gtfs_rows"};
  }
  void check_held(std::size_t more, const std::string& where) const {
    check_limit(held + more, limits.max_gtfs_buffered_stop_times, "max_gtfs_buffered_stop_times", where,
                "stop_times rows held (stop patterns, the current trip, trips spread over the file)");
  }
};

// --- routes.txt ---

void read_routes(ByteSource& in, Gtfs& g) {
  CsvStream csv(in, "routes.txt", g.limits, g.bounds());
  const auto c_id = csv.column("route_id"), c_type = csv.column("route_type");
  const auto c_short = csv.find_column("route_short_name"), c_long = csv.find_column("route_long_name"),
             c_colour = csv.find_column("route_color");
  while (csv.next()) {
    const auto where = csv.where();
    check_limit(g.routes.size() + 1, g.limits.max_gtfs_trips, "max_gtfs_trips", where, "routes (each needs a trip)");
    Route route;
    route.id = std::string(trim(csv.field(c_id)));
    if (route.id.empty()) throw LoadError(where, "empty route_id");
    check_text(route.id, g.limits.max_id_bytes, "max_id_bytes", where, "route_id");
    route.label = std::string(trim(csv.field(c_short)));
    if (route.label.empty()) route.label = std::string(trim(csv.field(c_long)));
    if (route.label.empty()) route.label = route.id;
    check_text(route.label, g.limits.max_name_bytes, "max_name_bytes", where, "route name");
    route.colour = colour_of(csv.field(c_colour));
    const long type = parse_integer(csv.field(c_type), where, "route_type");
    route.mode = type < 0 || type > 100'000 ? "" : gtfs_route_mode(static_cast<int>(type));
    if (!g.route_index.emplace(route.id, static_cast<std::uint32_t>(g.routes.size())).second)
      throw LoadError(where, "duplicate route_id " + quote_id(route.id));
    g.routes.push_back(std::move(route));
  }
  g.stats.routes = g.routes.size();
}

// --- trips.txt ---

void read_trips(ByteSource& in, Gtfs& g) {
  CsvStream csv(in, "trips.txt", g.limits, g.bounds());
  const auto c_id = csv.column("trip_id"), c_route = csv.column("route_id");
  const auto c_shape = csv.find_column("shape_id");
  while (csv.next()) {
    const auto where = csv.where();
    check_limit(g.trips.size() + 1, g.limits.max_gtfs_trips, "max_gtfs_trips", where, "trips");
    const auto id = trim(csv.field(c_id));
    if (id.empty()) throw LoadError(where, "empty trip_id");
    check_text(id, g.limits.max_id_bytes, "max_id_bytes", where, "trip_id");
    Trip trip;
    const auto route_id = trim(csv.field(c_route));
    const auto* route = find_id(g.route_index, route_id);
    if (!route) throw LoadError(where, "unknown route_id " + quote_id(route_id));
    trip.route = *route;
    g.routes[*route].has_trips = true;
    if (const auto shape = trim(csv.field(c_shape)); !shape.empty()) {
      check_text(shape, g.limits.max_id_bytes, "max_id_bytes", where, "shape_id");
      trip.shape = g.shape_index.try_emplace(std::string(shape), static_cast<std::uint32_t>(g.shape_index.size()))
                       .first->second;
    }
    if (!g.trip_index.emplace(std::string(id), static_cast<std::uint32_t>(g.trips.size())).second)
      throw LoadError(where, "duplicate trip_id " + quote_id(id));
    g.trips.push_back(trip);
  }
  g.stats.trips = g.trips.size();
}

// The modes read, and the routes and trips of them.
void choose_modes(const std::vector<std::string>& asked, Gtfs& g) {
  std::vector<std::string> present;
  for (const auto& route : g.routes)
    if (route.has_trips && !route.mode.empty() &&
        std::find(present.begin(), present.end(), route.mode) == present.end())
      present.push_back(route.mode);
  g.stats.modes = asked.empty() ? default_transit_modes(present) : asked;
  const auto asks = [&](const std::string& mode) {
    return std::find(g.stats.modes.begin(), g.stats.modes.end(), mode) != g.stats.modes.end();
  };
  for (auto& route : g.routes) {
    route.kept = route.has_trips && !route.mode.empty() && (asks(route.mode) || (route.mode == "tram" && asks("light_rail")));
    g.stats.routes_of_modes += route.kept ? 1 : 0;
  }
  for (const auto& trip : g.trips) g.stats.trips_of_modes += g.routes[trip.route].kept ? 1 : 0;
}

// --- stops.txt ---

struct RawStop {
  std::string id, name, parent;
  std::optional<geo::LonLat> pos;
  long type = 0;
  std::size_t row = 0;
};

std::vector<RawStop> read_raw_stops(ByteSource& in, Gtfs& g, IdMap<std::uint32_t>& index) {
  CsvStream csv(in, "stops.txt", g.limits, g.bounds());
  const auto c_id = csv.column("stop_id"), c_lat = csv.column("stop_lat"), c_lon = csv.column("stop_lon");
  const auto c_name = csv.find_column("stop_name"), c_type = csv.find_column("location_type"),
             c_parent = csv.find_column("parent_station");
  std::vector<RawStop> stops;
  while (csv.next()) {
    const auto where = csv.where();
    check_limit(stops.size() + 1, g.limits.max_gtfs_stops, "max_gtfs_stops", where, "stops");
    RawStop stop;
    stop.row = csv.row();
    stop.id = std::string(trim(csv.field(c_id)));
    if (stop.id.empty()) throw LoadError(where, "empty stop_id");
    check_text(stop.id, g.limits.max_id_bytes, "max_id_bytes", where, "stop_id");
    stop.name = std::string(trim(csv.field(c_name)));
    check_text(stop.name, g.limits.max_name_bytes, "max_name_bytes", where, "stop_name");
    stop.parent = std::string(trim(csv.field(c_parent)));
    if (!is_null_field(csv.field(c_type))) stop.type = parse_integer(csv.field(c_type), where, "location_type");
    if (!is_null_field(csv.field(c_lat)) || !is_null_field(csv.field(c_lon)))
      stop.pos = parse_position(csv.field(c_lat), csv.field(c_lon), where, "stop_lat", "stop_lon");
    if (!index.emplace(stop.id, static_cast<std::uint32_t>(stops.size())).second)
      throw LoadError(where, "duplicate stop_id " + quote_id(stop.id));
    stops.push_back(std::move(stop));
  }
  return stops;
}

// The root of each stop's parent_station chain (GTFS nests at most boarding area -> platform ->
// station; a longer chain is a loop).
std::vector<std::uint32_t> station_roots(const std::vector<RawStop>& stops, const IdMap<std::uint32_t>& index) {
  std::vector<std::uint32_t> root(stops.size(), kNone);
  for (std::uint32_t s = 0; s < stops.size(); ++s) {
    std::uint32_t at = s;
    for (int depth = 0; !stops[at].parent.empty(); ++depth) {
      if (root[at] != kNone) break;
      const auto* parent = find_id(index, stops[at].parent);
      const auto where = "stops.txt row " + std::to_string(stops[at].row);
      if (!parent) throw LoadError(where, "unknown parent_station " + quote_id(stops[at].parent));
      if (depth >= 4) throw LoadError(where, "parent_station chain of stop " + quote_id(stops[s].id) + " loops");
      at = *parent;
    }
    root[s] = root[at] != kNone ? root[at] : at;
  }
  return root;
}

void read_stops(ByteSource& in, Gtfs& g) {
  IdMap<std::uint32_t> index;
  const auto stops = read_raw_stops(in, g, index);
  const auto root = station_roots(stops, index);
  std::vector<std::uint32_t> station_of(stops.size(), kNone);
  for (std::uint32_t s = 0; s < stops.size(); ++s) {
    if (root[s] != s) continue;
    station_of[s] = static_cast<std::uint32_t>(g.stations.size());
    g.stations.push_back({stops[s].id, stops[s].name, stops[s].pos, 0, 0, 0, 0, 0, 0, kNone});
  }
  for (std::uint32_t s = 0; s < stops.size(); ++s) {
    auto& station = g.stations[station_of[root[s]]];
    if (root[s] != s && station.name.empty()) station.name = stops[s].name;
    if (root[s] == s || !stops[s].pos) continue;
    if (stops[s].type == 0) {
      station.lon += stops[s].pos->lon, station.lat += stops[s].pos->lat, ++station.stops;
    } else {
      station.other_lon += stops[s].pos->lon, station.other_lat += stops[s].pos->lat, ++station.others;
    }
  }
  // stop_times name stops; from here on a stop id leads to its station.
  for (auto& [id, s] : index) s = station_of[root[s]];
  g.station_of_stop = std::move(index);
}

// --- patterns ---

// The pattern of a trip from its rows (reordered); kNone for fewer than two stations.
std::uint32_t make_pattern(const Trip& trip, std::vector<Row>& rows, Gtfs& g, const std::string& where) {
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.sequence < b.sequence; });
  std::vector<std::uint32_t> key{trip.route};
  for (const auto& row : rows)
    if (key.size() == 1 || key.back() != row.station) key.push_back(row.station);
  if (key.size() < 3) return kNone;
  // One direction stands for both: the lexicographically smaller.
  const bool reversed = std::lexicographical_compare(key.rbegin(), key.rend() - 1, key.begin() + 1, key.end());
  if (reversed) std::reverse(key.begin() + 1, key.end());
  const auto [it, fresh] = g.pattern_index.try_emplace(std::move(key), static_cast<std::uint32_t>(g.patterns.size()));
  if (fresh) {
    g.check_held(it->first.size() - 1, where);
    g.held += it->first.size() - 1;
    g.patterns.push_back({trip.route, &it->first});
  }
  auto& pattern = g.patterns[it->second];
  if (pattern.shape == kNone && trip.shape != kNone) {
    pattern.shape = trip.shape;
    pattern.shape_reversed = reversed;
  }
  return it->second;
}

// --- stop_times.txt ---

// Streams stop_times.txt: `on_row` gets each row's trip index (validated), stop_id and
// stop_sequence fields. The trip of consecutive rows is looked up once.
template <class OnRow>
std::size_t stream_stop_times(ByteSource& in, Gtfs& g, OnRow&& on_row) {
  CsvStream csv(in, "stop_times.txt", g.limits, g.bounds());
  const auto c_trip = csv.column("trip_id"), c_stop = csv.column("stop_id"), c_seq = csv.column("stop_sequence");
  std::string current_id;
  std::uint32_t current = kNone;
  while (csv.next()) {
    const auto trip_id = trim(csv.field(c_trip));
    if (current == kNone || trip_id != current_id) {
      const auto* trip = find_id(g.trip_index, trip_id);
      if (!trip) throw LoadError(csv.where(), "unknown trip_id " + quote_id(trip_id));
      current = *trip;
      current_id.assign(trip_id);
    }
    on_row(csv, current, trim(csv.field(c_stop)), csv.field(c_seq));
  }
  return csv.rows_read();
}

std::uint32_t station_of_row(const CsvStream& csv, const Gtfs& g, std::string_view stop_id) {
  const auto* station = find_id(g.station_of_stop, stop_id);
  if (!station) throw LoadError(csv.where(), "unknown stop_id " + quote_id(stop_id));
  return *station;
}

// First pass: every row validated; the rows of each kept trip, while they run, make its pattern.
void read_stop_times(ByteSource& in, Gtfs& g) {
  std::uint32_t running = kNone;
  std::vector<Row> run;
  const auto end_run = [&](const std::string& where) {
    if (running == kNone || run.empty()) return;
    auto& trip = g.trips[running];
    if (trip.runs == 0) {
      trip.runs = 1;
      trip.pattern = make_pattern(trip, run, g, where);
    } else if (trip.runs == 1) {  // its rows are spread over the file: read again (pass 2)
      trip.runs = 2;
      trip.pattern = kNone;
      ++g.stats.unsorted_trips;
    }
    run.clear();
  };
  g.stats.stop_times = stream_stop_times(in, g, [&](const CsvStream& csv, std::uint32_t trip, std::string_view stop,
                                                    std::string_view sequence) {
    const auto station = station_of_row(csv, g, stop);
    const auto seq = parse_sequence(sequence, csv.where(), "stop_sequence");
    if (trip != running) {
      end_run(csv.where());
      running = trip;
    }
    if (!g.routes[g.trips[trip].route].kept) return;
    g.check_held(run.size() + 1, csv.where());
    run.push_back({seq, station});
  });
  end_run("stop_times.txt");
}

// Second pass, for the trips whose rows are spread over the file: their rows, held until the end.
void read_spread_trips(ByteSource& in, Gtfs& g) {
  std::unordered_map<std::uint32_t, std::vector<Row>> rows;
  std::size_t held = 0;
  stream_stop_times(in, g, [&](const CsvStream& csv, std::uint32_t trip, std::string_view stop, std::string_view sequence) {
    if (g.trips[trip].runs != 2) return;
    g.check_held(++held, csv.where());
    rows[trip].push_back({parse_sequence(sequence, csv.where(), "stop_sequence"), station_of_row(csv, g, stop)});
  });
  std::vector<std::uint32_t> spread;
  for (const auto& [trip, r] : rows) spread.push_back(trip);
  std::sort(spread.begin(), spread.end());  // patterns numbered in trip order, whatever the hash order
  for (auto trip : spread) g.trips[trip].pattern = make_pattern(g.trips[trip], rows[trip], g, "stop_times.txt");
}

// --- shapes.txt ---

struct ShapePoint {
  std::uint32_t sequence;
  geo::LonLat pos;
};

// The positions of the shapes in `needed` (indices into shape_index), in sequence order.
std::vector<std::vector<geo::LonLat>> read_shapes(ByteSource& in, const Gtfs& g, const std::vector<bool>& needed) {
  CsvStream csv(in, "shapes.txt", g.limits, g.bounds());
  const auto c_id = csv.column("shape_id"), c_lat = csv.column("shape_pt_lat"), c_lon = csv.column("shape_pt_lon"),
             c_seq = csv.column("shape_pt_sequence");
  std::vector<std::vector<ShapePoint>> points(needed.size());
  std::size_t held = 0;
  std::string current_id;
  std::uint32_t current = kNone;  // kNone: a shape no kept pattern needs (or no trip names)
  bool started = false;
  while (csv.next()) {
    const auto id = trim(csv.field(c_id));
    if (!started || id != current_id) {
      const auto* shape = find_id(g.shape_index, id);
      current = shape && needed[*shape] ? *shape : kNone;
      current_id.assign(id);
      started = true;
    }
    if (current == kNone) continue;
    const auto where = csv.where();
    check_limit(++held, g.limits.max_gtfs_shape_points, "max_gtfs_shape_points", where, "shape positions held");
    points[current].push_back({parse_sequence(csv.field(c_seq), where, "shape_pt_sequence"),
                               parse_position(csv.field(c_lat), csv.field(c_lon), where, "shape_pt_lat", "shape_pt_lon")});
  }
  std::vector<std::vector<geo::LonLat>> shapes(needed.size());
  for (std::size_t s = 0; s < points.size(); ++s) {
    auto& p = points[s];
    std::stable_sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return a.sequence < b.sequence; });
    shapes[s].reserve(p.size());
    for (const auto& point : p) shapes[s].push_back(point.pos);
    std::vector<ShapePoint>().swap(p);
  }
  return shapes;
}

// --- stations along a shape ---

// Metres east and north of an origin (equirectangular: fine along one route).
struct LocalFrame {
  geo::LonLat origin;
  double kx, ky;
  explicit LocalFrame(geo::LonLat o)
      : origin(o), kx(111'320.0 * std::cos(o.lat * 3.14159265358979323846 / 180.0)), ky(110'574.0) {}
  std::pair<double, double> operator()(geo::LonLat p) const { return {(p.lon - origin.lon) * kx, (p.lat - origin.lat) * ky}; }
};

// A point on a polyline: on segment `segment` (from point segment to segment + 1) at `t`.
struct Along {
  std::size_t segment = 0;
  double t = 0;
  double param() const { return static_cast<double>(segment) + t; }
};

// Where each station lies along the shape, in order (never going back); nullopt when a station
// is more than kMaxShapeOffsetMetres from the rest of the shape.
std::optional<std::vector<Along>> project_stations(const std::vector<geo::LonLat>& stations,
                                                   const std::vector<geo::LonLat>& shape) {
  if (shape.size() < 2) return std::nullopt;
  const LocalFrame frame(shape.front());
  std::vector<std::pair<double, double>> xy;
  xy.reserve(shape.size());
  for (const auto& p : shape) xy.push_back(frame(p));
  std::vector<Along> out;
  std::vector<std::pair<double, double>> candidates;  // (t, distance) per segment from prev
  Along prev;
  for (const auto& station : stations) {
    const auto [px, py] = frame(station);
    candidates.clear();
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = prev.segment; j + 1 < xy.size(); ++j) {
      const double ax = xy[j].first, ay = xy[j].second;
      const double dx = xy[j + 1].first - ax, dy = xy[j + 1].second - ay;
      const double length2 = dx * dx + dy * dy;
      double t = length2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / length2 : 0.0;
      t = std::clamp(t, j == prev.segment ? prev.t : 0.0, 1.0);
      const double d = std::hypot(ax + t * dx - px, ay + t * dy - py);
      candidates.emplace_back(t, d);
      best = std::min(best, d);
    }
    if (!(best <= kMaxShapeOffsetMetres)) return std::nullopt;
    const auto d = [&](std::size_t k) { return candidates[k].second; };
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      const bool local_minimum = (k == 0 || d(k) <= d(k - 1)) && (k + 1 == candidates.size() || d(k) <= d(k + 1));
      if (local_minimum && d(k) <= best + kShapeSlackMetres) {
        prev = {prev.segment + k, candidates[k].first};
        break;
      }
    }
    out.push_back(prev);
  }
  return out;
}

// The geometry of the edge between two stations: the stations, and the shape's points between.
std::vector<geo::LonLat> edge_geometry(geo::LonLat from, geo::LonLat to, const std::vector<geo::LonLat>& shape,
                                       const Along& a, const Along& b) {
  std::vector<geo::LonLat> out{from};
  const auto add = [&](geo::LonLat p) {
    if (p.lon != out.back().lon || p.lat != out.back().lat) out.push_back(p);  // no zero-length pieces
  };
  for (std::size_t k = a.segment + 1; k < shape.size() && static_cast<double>(k) < b.param(); ++k)
    if (static_cast<double>(k) > a.param()) add(shape[k]);
  add(to);
  if (out.size() < 2) out.push_back(to);  // two stations at one position: MetroEdge needs two
  return out;
}

// --- the network ---

class NetworkBuilder {
 public:
  NetworkBuilder(Gtfs& g, const std::string& source) : g_(g), source_(source), builder_(g.limits) {}

  // Lines first, in the order of routes.txt.
  void add_lines(const std::vector<bool>& used) {
    line_of_route_.assign(g_.routes.size(), kNone);
    for (std::size_t r = 0; r < g_.routes.size(); ++r) {
      if (!used[r]) continue;
      const auto& route = g_.routes[r];
      line_of_route_[r] = builder_.line({route.id, route.label, route.colour, {}}, "routes.txt route " + quote_id(route.id));
      ++g_.stats.lines;
    }
  }

  // The edges of a pattern, along `geometry` (per edge) or straight.
  void add_pattern(const Pattern& p, const std::vector<std::uint32_t>& stations,
                   const std::vector<std::vector<geo::LonLat>>* geometry) {
    const auto line = line_of_route_[p.route];
    const auto where = "routes.txt route " + quote_id(g_.routes[p.route].id);
    for (std::size_t i = 0; i + 1 < stations.size(); ++i) {
      const auto a = node(stations[i]), b = node(stations[i + 1]);
      if (!done_.insert({line, std::min(a, b), std::max(a, b)}).second) continue;  // another pattern had it
      if (!geometry) {
        builder_.connect(a, b, line, where);
        continue;
      }
      model::MetroEdge edge;
      edge.from = a;
      edge.to = b;
      edge.lines = {line};
      edge.geometry = (*geometry)[i];
      builder_.add_edge(std::move(edge), where);
    }
  }

  geo::LonLat position(std::uint32_t station) { return builder_.pos(node(station)); }

  model::MetroNetwork finish() && { return std::move(builder_).finish(source_); }

 private:
  std::uint32_t node(std::uint32_t s) {
    auto& station = g_.stations[s];
    if (station.node != kNone) return station.node;
    const auto where = "stops.txt station " + quote_id(station.stop_id);
    geo::LonLat pos;
    if (station.pos) pos = *station.pos;
    else if (station.stops) pos = {station.lon / double(station.stops), station.lat / double(station.stops)};
    else if (station.others) pos = {station.other_lon / double(station.others), station.other_lat / double(station.others)};
    else throw LoadError(where, "no coordinates (nor any of its stops)");
    const std::string id = "s" + station.stop_id;
    station.node = builder_.add_node({id, id, station.name.empty() ? station.stop_id : station.name, pos}, where);
    ++g_.stats.stations;
    return station.node;
  }

  Gtfs& g_;
  const std::string& source_;
  MetroBuilder builder_;
  std::vector<std::uint32_t> line_of_route_;
  std::set<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> done_;  // (line, node, node)
};

// The stations of a pattern in the direction of its shape's trip.
std::vector<std::uint32_t> oriented_stations(const Pattern& p) {
  std::vector<std::uint32_t> out(p.key->begin() + 1, p.key->end());
  if (p.shape_reversed) std::reverse(out.begin(), out.end());
  return out;
}

model::MetroNetwork build_network(Gtfs& g, const Feed& feed) {
  // The patterns trips run (a spread trip's partial patterns may have none).
  for (const auto& trip : g.trips)
    if (trip.pattern != kNone) ++g.patterns[trip.pattern].trips;
  std::vector<std::uint32_t> used;
  std::vector<bool> routes_used(g.routes.size(), false);
  for (std::uint32_t p = 0; p < g.patterns.size(); ++p)
    if (g.patterns[p].trips) {
      used.push_back(p);
      routes_used[g.patterns[p].route] = true;
    }
  g.stats.patterns = used.size();
  if (used.empty())
    throw LoadError(feed.name(), "no route of the modes " + join(g.stats.modes) + " has a trip of two stations (" +
                                     std::to_string(g.stats.routes_of_modes) + " routes, " +
                                     std::to_string(g.stats.trips_of_modes) + " trips of those modes)");

  std::vector<bool> needed(g.shape_index.size(), false);
  for (auto p : used)
    if (g.patterns[p].shape != kNone) needed[g.patterns[p].shape] = true;
  std::vector<std::vector<geo::LonLat>> shapes(needed.size());
  if (std::find(needed.begin(), needed.end(), true) != needed.end())
    if (auto in = feed.open("shapes.txt")) shapes = read_shapes(*in, g, needed);

  NetworkBuilder net(g, feed.name());
  net.add_lines(routes_used);
  // Patterns along their shapes first: an edge keeps the geometry it is first given.
  std::vector<std::uint32_t> straight;
  std::vector<bool> shape_used(shapes.size(), false);
  for (auto p : used) {
    util::check_stop();
    const auto& pattern = g.patterns[p];
    if (pattern.shape == kNone || shapes[pattern.shape].size() < 2) {
      straight.push_back(p);
      continue;
    }
    const auto stations = oriented_stations(pattern);
    std::vector<geo::LonLat> positions;
    for (auto s : stations) positions.push_back(net.position(s));
    const auto& shape = shapes[pattern.shape];
    const auto along = project_stations(positions, shape);
    if (!along) {
      ++g.stats.patterns_off_shape;
      straight.push_back(p);
      continue;
    }
    std::vector<std::vector<geo::LonLat>> geometry;
    for (std::size_t i = 0; i + 1 < stations.size(); ++i)
      geometry.push_back(edge_geometry(positions[i], positions[i + 1], shape, (*along)[i], (*along)[i + 1]));
    net.add_pattern(pattern, stations, &geometry);
    shape_used[pattern.shape] = true;
  }
  for (auto p : straight) net.add_pattern(g.patterns[p], oriented_stations(g.patterns[p]), nullptr);
  g.stats.shapes_used = static_cast<std::size_t>(std::count(shape_used.begin(), shape_used.end(), true));
  return std::move(net).finish();
}

model::MetroNetwork load(const std::string& path, const std::vector<std::string>& asked, const ImportLimits& limits,
                         GtfsStats* stats_out) {
  const Feed feed(path);
  Gtfs g(limits);
  read_routes(*feed.require("routes.txt"), g);
  read_trips(*feed.require("trips.txt"), g);
  choose_modes(asked, g);
  read_stops(*feed.require("stops.txt"), g);
  read_stop_times(*feed.require("stop_times.txt"), g);
  if (g.stats.unsorted_trips) read_spread_trips(*feed.require("stop_times.txt"), g);
  auto net = build_network(g, feed);
  if (stats_out) *stats_out = g.stats;
  return net;
}

}  // namespace

std::string gtfs_route_mode(int type) {
  switch (type) {
    case 0: return "tram";
    case 1: return "subway";
    case 2: return "train";
    case 3: return "bus";
    case 4: return "ferry";
    case 5: return "cable_tram";
    case 6: return "aerial_lift";
    case 7: return "funicular";
    case 11: return "trolleybus";
    case 12: return "monorail";
    default: break;
  }
  if (type == 405) return "monorail";
  if ((type >= 100 && type < 200) || (type >= 300 && type < 400)) return "train";
  if (type >= 200 && type < 300) return "coach";
  if (type >= 400 && type < 700) return "subway";  // urban railway, metro, underground
  if (type >= 700 && type < 800) return "bus";
  if (type >= 800 && type < 900) return "trolleybus";
  if (type >= 900 && type < 1000) return "tram";
  if ((type >= 1000 && type < 1100) || (type >= 1200 && type < 1300)) return "ferry";
  if (type >= 1300 && type < 1400) return "aerial_lift";
  if (type >= 1400 && type < 1500) return "funicular";
  return "";
}

const std::vector<std::string>& gtfs_modes() { return kModes; }

model::MetroNetwork load_metro_gtfs(const std::string& path, const std::vector<std::string>& modes,
                                    const ImportLimits& limits, GtfsStats* stats) {
  const std::string source = feed_name(path);
  for (const auto& mode : modes)
    if (std::find(kModes.begin(), kModes.end(), mode) == kModes.end())
      throw LoadError(source, "unknown transit mode " + quote_id(mode) + " (known: " + join(kModes) + ")");
  try {
    return load(path, modes, limits, stats);
  } catch (const LoadError&) {
    throw;
  } catch (const util::Stopped&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw LoadError(source, std::string("cannot read the GTFS feed: ") + e.what());
  }
}

}  // namespace tourmap::load
