// GTFS import benchmark (issue 16): generates a feed with 1,000,000 stop_times rows (by default)
// into a temporary folder, zips it (libzip, deflate), and imports it with load_metro_gtfs from
// the folder, from the zip, and from a folder whose stop_times.txt is not grouped by trip (the
// rows of 1,000 trips at a time interleaved, so every trip is read in the second pass). Prints
// rows, seconds, rows/s and the peak resident memory of each import (VmHWM, reset before each
// through /proc/self/clear_refs) beside the resident memory before it.
//
// The feed: 100 subway routes of 25 stations each on a grid of 2,000 stations (each a parent
// station with two platforms; routes share stations), 400 trips a route, half of them back,
// every fourth by the other platforms and through a detour station (two patterns a route); one
// shape a route, four positions between stations. stop_times.txt has the columns of a real feed
// (times, pickup and drop-off types, distances), ~62 bytes a row.
//
//   build/bench/gtfs_bench [--rows N] [--keep DIR]

#include "process_memory.hpp"
#include "load/load_error.hpp"
#include "load/metro_gtfs.hpp"

#include <unistd.h>
#include <zip.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace tourmap;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

constexpr int kRoutes = 100;
constexpr int kStopsPerTrip = 25;
constexpr int kGrid = 50;  // stations per grid row
constexpr int kStations = 2000;

struct Feed {
  int routes = kRoutes;
  int trips_per_route = 0;
  std::size_t rows = 0;
};

double station_lat(int s) { return 48.15 + (s / kGrid) * 0.004; }
double station_lon(int s) { return 16.25 + (s % kGrid) * 0.006; }
// The i-th station of route r (routes cross the grid and share stations).
int route_station(int r, int i) { return (r * 37 + i * (1 + r % 7) * kGrid / 10 + i) % kStations; }
// The detour of every fourth trip: another station instead of the middle one.
int detour_station(int r) { return (route_station(r, kStopsPerTrip / 2) + kStations / 2) % kStations; }

std::string hms(int seconds) {
  char out[16];
  std::snprintf(out, sizeof out, "%02d:%02d:%02d", seconds / 3600, seconds / 60 % 60, seconds % 60);
  return out;
}

class Writer {
 public:
  explicit Writer(const fs::path& path) : file_(std::fopen(path.c_str(), "wb")) {
    if (!file_) throw std::runtime_error("cannot write " + path.string());
  }
  ~Writer() { std::fclose(file_); }
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;
  __attribute__((format(printf, 2, 3))) void operator()(const char* format, ...) {
    va_list args;
    va_start(args, format);
    std::vfprintf(file_, format, args);
    va_end(args);
  }

 private:
  std::FILE* file_;
};

// The stations of trip t of route r, in its direction.
std::vector<int> trip_stations(int r, int t) {
  std::vector<int> out;
  for (int i = 0; i < kStopsPerTrip; ++i) out.push_back(t % 4 == 3 && i == kStopsPerTrip / 2 ? detour_station(r) : route_station(r, i));
  if (t % 2 == 1) std::reverse(out.begin(), out.end());
  return out;
}

void write_stop_time(Writer& w, int r, int t, int i, int station) {
  const int time = 5 * 3600 + t * 150 + i * 90;
  w("trip-%03d-%04d,%s,%s,stop-%04d-%c,%d,0,0,%.1f\n", r, t, hms(time).c_str(), hms(time + 20).c_str(), station,
    t % 4 == 3 ? 'b' : 'a', i + 1, i * 640.5);
}

// stop_times.txt grouped by trip, or the trips of each block of `interleave` trips interleaved.
void write_stop_times(const fs::path& dir, const Feed& feed, int interleave) {
  Writer w(dir / "stop_times.txt");
  w("trip_id,arrival_time,departure_time,stop_id,stop_sequence,pickup_type,drop_off_type,shape_dist_traveled\n");
  std::vector<std::pair<int, int>> trips;  // (route, trip)
  for (int r = 0; r < feed.routes; ++r)
    for (int t = 0; t < feed.trips_per_route; ++t) trips.push_back({r, t});
  for (std::size_t block = 0; block < trips.size(); block += static_cast<std::size_t>(interleave)) {
    const std::size_t end = std::min(trips.size(), block + static_cast<std::size_t>(interleave));
    if (interleave == 1) {
      const auto [r, t] = trips[block];
      const auto stations = trip_stations(r, t);
      for (int i = 0; i < kStopsPerTrip; ++i) write_stop_time(w, r, t, i, stations[static_cast<std::size_t>(i)]);
      continue;
    }
    for (int i = 0; i < kStopsPerTrip; ++i)
      for (std::size_t k = block; k < end; ++k) {
        const auto [r, t] = trips[k];
        write_stop_time(w, r, t, i, trip_stations(r, t)[static_cast<std::size_t>(i)]);
      }
  }
}

Feed write_feed(const fs::path& dir, std::size_t rows, int interleave) {
  fs::create_directories(dir);
  Feed feed;
  feed.trips_per_route = static_cast<int>((rows + kRoutes * kStopsPerTrip - 1) / (kRoutes * kStopsPerTrip));
  feed.rows = static_cast<std::size_t>(feed.trips_per_route) * kRoutes * kStopsPerTrip;
  {
    Writer w(dir / "agency.txt");
    w("agency_id,agency_name,agency_url,agency_timezone\nbench,Bench Transit,https://example.org,Europe/Vienna\n");
  }
  {
    Writer w(dir / "stops.txt");
    w("stop_id,stop_code,stop_name,stop_desc,stop_lat,stop_lon,location_type,parent_station,wheelchair_boarding\n");
    for (int s = 0; s < kStations; ++s) {
      w("station-%04d,,\"Station %d, Grid\",,%.6f,%.6f,1,,1\n", s, s, station_lat(s), station_lon(s));
      for (char p : {'a', 'b'})
        w("stop-%04d-%c,%d%c,Station %d,Platform %c,%.6f,%.6f,0,station-%04d,1\n", s, p, s, p, s, p,
          station_lat(s) + (p == 'a' ? 0.00005 : -0.00005), station_lon(s), s);
    }
  }
  {
    Writer w(dir / "routes.txt");
    w("route_id,agency_id,route_short_name,route_long_name,route_type,route_color,route_text_color\n");
    for (int r = 0; r < feed.routes; ++r) w("R%03d,bench,U%d,\"Line %d\",1,%06X,FFFFFF\n", r, r, r, (r * 0x2468AC) & 0xFFFFFF);
  }
  {
    Writer w(dir / "trips.txt");
    w("route_id,service_id,trip_id,trip_headsign,direction_id,shape_id\n");
    for (int r = 0; r < feed.routes; ++r)
      for (int t = 0; t < feed.trips_per_route; ++t)
        w("R%03d,weekday,trip-%03d-%04d,Terminus,%d,%s\n", r, r, t, t % 2, t % 4 == 0 ? ("shape-" + std::to_string(r)).c_str() : "");
  }
  {
    Writer w(dir / "shapes.txt");
    w("shape_id,shape_pt_lat,shape_pt_lon,shape_pt_sequence,shape_dist_traveled\n");
    for (int r = 0; r < feed.routes; ++r) {
      int seq = 0;
      for (int i = 0; i + 1 < kStopsPerTrip; ++i) {
        const int a = route_station(r, i), b = route_station(r, i + 1);
        for (int k = 0; k < 5; ++k) {  // the station, then four points bending off the straight line
          const double f = k / 5.0, bend = k == 0 ? 0 : 0.0004 * std::sin(f * 3.14159);
          w("shape-%d,%.6f,%.6f,%d,%.1f\n", r, station_lat(a) + f * (station_lat(b) - station_lat(a)) + bend,
            station_lon(a) + f * (station_lon(b) - station_lon(a)), seq, seq * 128.0);
          ++seq;
        }
      }
      const int last = route_station(r, kStopsPerTrip - 1);
      w("shape-%d,%.6f,%.6f,%d,%.1f\n", r, station_lat(last), station_lon(last), seq, seq * 128.0);
    }
  }
  write_stop_times(dir, feed, interleave);
  return feed;
}

void write_zip(const fs::path& dir, const fs::path& zip_path) {
  int error = 0;
  zip_t* zip = zip_open(zip_path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (!zip) throw std::runtime_error("cannot create " + zip_path.string());
  for (const auto& entry : fs::directory_iterator(dir)) {
    zip_source_t* source = zip_source_file(zip, entry.path().c_str(), 0, -1);
    if (!source || zip_file_add(zip, entry.path().filename().c_str(), source, ZIP_FL_OVERWRITE) < 0)
      throw std::runtime_error("cannot add " + entry.path().string());
  }
  if (zip_close(zip) != 0) throw std::runtime_error("cannot write " + zip_path.string());
}

using tourmap::bench::reset_peak;
using tourmap::bench::status_mb;

double size_mb(const fs::path& path) {
  std::uintmax_t bytes = 0;
  if (fs::is_directory(path))
    for (const auto& e : fs::directory_iterator(path)) bytes += e.file_size();
  else
    bytes = fs::file_size(path);
  return static_cast<double>(bytes) / (1024.0 * 1024.0);
}

struct Result {
  std::string input;
  double size_mb = 0;
  load::GtfsStats stats;
  std::size_t nodes = 0, edges = 0;
  double seconds = 0, rss_before = 0, peak = 0;
  bool peak_reset = false;
};

Result import(const std::string& label, const fs::path& path) {
  Result r;
  r.input = label;
  r.size_mb = size_mb(path);
  r.peak_reset = reset_peak();
  r.rss_before = status_mb("VmRSS:");
  const auto start = Clock::now();
  const auto net = load::load_metro_gtfs(path.string(), {}, {}, &r.stats);
  r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  r.peak = status_mb("VmHWM:");
  r.nodes = net.nodes.size();
  r.edges = net.edges.size();
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t rows = 1'000'000;
  std::string keep;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--rows" && i + 1 < argc) rows = std::strtoull(argv[++i], nullptr, 10);
    else if (arg == "--keep" && i + 1 < argc) keep = argv[++i];
    else {
      std::fprintf(stderr, "usage: gtfs_bench [--rows N] [--keep DIR]\n");
      return 2;
    }
  }
  const fs::path root = keep.empty() ? fs::temp_directory_path() / ("tourmap-gtfs-bench-" + std::to_string(::getpid())) : fs::path(keep);
  try {
    std::printf("Generating a GTFS feed of %zu stop_times rows in %s ...\n", rows, root.c_str());
    const auto t0 = Clock::now();
    const Feed feed = write_feed(root / "feed", rows, 1);
    write_zip(root / "feed", root / "feed.zip");
    write_feed(root / "unsorted", rows, 1000);
    std::printf("generated in %.1f s: %d routes, %d trips, %zu stop_times rows\n\n",
                std::chrono::duration<double>(Clock::now() - t0).count(), feed.routes, feed.routes * feed.trips_per_route,
                feed.rows);

    std::vector<Result> results;
    results.push_back(import("folder", root / "feed"));
    results.push_back(import("zip", root / "feed.zip"));
    results.push_back(import("folder, stop_times not grouped by trip", root / "unsorted"));

    std::printf("GTFS import (load_metro_gtfs; peak RSS = VmHWM during the import%s)\n\n",
                results.front().peak_reset ? ", reset before each" : ", NOT reset: clear_refs refused");
    std::printf("| input | size MB | stop_times rows | stations | edges | lines | patterns | shapes | read twice | seconds | rows/s | RSS before MB | peak RSS MB |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const auto& r : results)
      std::printf("| %s | %.1f | %zu | %zu | %zu | %zu | %zu | %zu | %zu trips | %.3f | %.0f | %.1f | %.1f |\n", r.input.c_str(),
                  r.size_mb, r.stats.stop_times, r.nodes, r.edges, r.stats.lines, r.stats.patterns, r.stats.shapes_used,
                  r.stats.unsorted_trips, r.seconds, static_cast<double>(r.stats.stop_times) / r.seconds, r.rss_before,
                  r.peak);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gtfs_bench: %s\n", e.what());
    if (keep.empty()) fs::remove_all(root);
    return 1;
  }
  if (keep.empty()) fs::remove_all(root);
  return 0;
}
