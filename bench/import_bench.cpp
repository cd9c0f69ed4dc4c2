// Import benchmark: every file the sample manifest imports from the shared data directory,
// parsed alone (the core loader: the baseline) and imported (loader + one SQLite transaction
// into a fresh database). Prints Google Benchmark's table, then a summary:
// file, nodes/edges/stations/POIs, seconds, rows/s, and import time relative to parse time.
// A road import reads its extract twice (roads, then the context layers); the context loader
// alone is measured too (context/FILE) and summarised against the roads' parse.
//
//   build/bench/import_bench [--data-dir DIR] [google benchmark flags]

#include "load/file.hpp"
#include "load/metro_load.hpp"
#include "load/osm_context.hpp"
#include "load/osm_roads.hpp"
#include "load/poi_load.hpp"
#include "store/importer.hpp"
#include "store/manifest.hpp"
#include "store/migrate.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace {

using namespace tourmap;
using Clock = std::chrono::steady_clock;

struct Counts {
  std::size_t nodes = 0, edges = 0, stations = 0, pois = 0, rows = 0;
};

// The context layers of each road extract, parsed alone.
struct ContextCounts {
  std::size_t areas = 0, sea = 0, lines = 0, places = 0, points = 0;
  double parse_s = 0;
  int runs = 0;
};
std::map<std::string, ContextCounts> context_results;

struct Case {
  std::string file;  // as named in the summary
  std::string kind;  // metro | pois | roads
  std::function<Counts()> parse;
  std::function<void(store::Db&)> import;
  std::function<void(store::Db&)> prepare;  // what must exist first (the city, for POIs)
};

struct Measured {
  Counts counts;
  double parse_s = 0, import_s = 0;
  int parse_runs = 0, import_runs = 0;
};
std::map<std::string, Measured> results;

Counts metro_counts(const model::MetroNetwork& net) {
  return {net.nodes.size(), net.edges.size(), net.station_count(), 0, net.nodes.size() + net.edges.size() + net.lines.size()};
}

model::MetroNetwork load_metro(const store::MetroImport& m) { return store::load_metro_files(m); }

std::vector<Case> cases_from(const store::Manifest& manifest) {
  std::vector<Case> cases;
  std::map<std::string, store::MetroImport> metro_by_city;
  for (auto m : manifest.metros) {
    m.force = true;
    metro_by_city[m.city.id] = m;
    std::string name;
    for (const auto& f : m.files) {
      if (!name.empty()) name += '+';
      name += load::file_name(f);
    }
    cases.push_back({name, "metro", [m] { return metro_counts(load_metro(m)); },
                     [m](store::Db& db) { store::import_metro(db, m); }, nullptr});
  }
  for (auto p : manifest.pois) {
    p.force = true;
    auto city = metro_by_city.at(p.city_id);
    cases.push_back({load::file_name(p.file), "pois",
                     [p] {
                       auto pois = load::load_pois(p.file, {p.default_category});
                       return Counts{0, 0, 0, pois.size(), pois.size()};
                     },
                     [p](store::Db& db) { store::import_pois(db, p); },
                     [city](store::Db& db) { store::import_metro(db, city); }});
  }
  for (auto r : manifest.roads) {
    r.force = true;
    cases.push_back({load::file_name(r.file), "roads",
                     [r] {
                       auto net = load::load_osm_roads(r.file);
                       return Counts{net.nodes.size(), net.edges.size(), 0, 0,
                                     net.nodes.size() + net.ways.size() + net.edges.size()};
                     },
                     [r](store::Db& db) { store::import_roads(db, r); }, nullptr});
  }
  return cases;
}

void bench_context(benchmark::State& state, const std::string& file, const std::string& name) {
  auto& m = context_results[name];
  for (auto _ : state) {
    auto start = Clock::now();
    load::OsmContextStats stats;
    const auto layers = load::load_osm_context(file, &stats);
    m.parse_s += std::chrono::duration<double>(Clock::now() - start).count();
    ++m.runs;
    m.areas = layers.areas.size();
    m.sea = stats.sea_rings;
    m.lines = layers.lines.size();
    m.places = layers.places.size();
    m.points = stats.points;
  }
  state.counters["points"] = static_cast<double>(m.points);
}

void bench_parse(benchmark::State& state, const Case& c) {
  auto& m = results[c.file];
  for (auto _ : state) {
    auto start = Clock::now();
    m.counts = c.parse();
    m.parse_s += std::chrono::duration<double>(Clock::now() - start).count();
    ++m.parse_runs;
  }
  state.counters["rows"] = static_cast<double>(m.counts.rows);
  state.counters["rows/s"] = benchmark::Counter(static_cast<double>(m.counts.rows), benchmark::Counter::kIsRate);
}

void bench_import(benchmark::State& state, const Case& c, const std::string& dir) {
  auto& m = results[c.file];
  int run = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto path = dir + "/bench-" + std::to_string(run++) + ".db";
    std::filesystem::remove(path);
    std::filesystem::remove(path + "-wal");
    std::filesystem::remove(path + "-shm");
    {
      store::Db db(path);
      store::migrate(db);
      if (c.prepare) c.prepare(db);
      state.ResumeTiming();
      auto start = Clock::now();
      c.import(db);
      m.import_s += std::chrono::duration<double>(Clock::now() - start).count();
      ++m.import_runs;
      state.PauseTiming();
    }
    std::filesystem::remove(path);
    std::filesystem::remove(path + "-wal");
    std::filesystem::remove(path + "-shm");
    state.ResumeTiming();
  }
  state.counters["rows"] = static_cast<double>(m.counts.rows);
  state.counters["rows/s"] = benchmark::Counter(static_cast<double>(m.counts.rows), benchmark::Counter::kIsRate);
}

void print_summary(const std::vector<Case>& cases) {
  std::printf("\nImport summary (mean per run; baseline = parse only, same run)\n\n");
  std::printf("| file | kind | nodes | edges | stations | POIs | rows | parse s | import s | rows/s (import) | import/parse |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& c : cases) {
    const auto& m = results[c.file];
    if (!m.parse_runs || !m.import_runs) continue;
    double parse = m.parse_s / m.parse_runs, import = m.import_s / m.import_runs;
    std::printf("| %s | %s | %zu | %zu | %zu | %zu | %zu | %.4f | %.4f | %.0f | %.2fx |\n", c.file.c_str(),
                c.kind.c_str(), m.counts.nodes, m.counts.edges, m.counts.stations, m.counts.pois, m.counts.rows, parse,
                import, m.counts.rows / import, import / parse);
  }
  std::printf("\nContext layers per road extract (load_osm_context alone; baseline = the roads' parse, same run)\n\n");
  std::printf("| file | areas | of them sea | lines | places | points | size (16 B/point) | parse s | vs roads parse |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& [file, m] : context_results) {
    if (!m.runs) continue;
    const auto& roads = results[file];
    const double parse = m.parse_s / m.runs;
    const double roads_parse = roads.parse_runs ? roads.parse_s / roads.parse_runs : 0;
    std::printf("| %s | %zu | %zu | %zu | %zu | %zu | %.2f MB | %.4f | %.2fx |\n", file.c_str(), m.areas, m.sea, m.lines,
                m.places, m.points, static_cast<double>(m.points) * 16 / 1e6, parse,
                roads_parse > 0 ? parse / roads_parse : 0.0);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string data_dir = TOURMAP_DEFAULT_DATA_DIR;
  if (const char* env = std::getenv("TOURMAP_DATA_DIR")) data_dir = env;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--data-dir" && i + 1 < argc) {
      data_dir = argv[++i];
      continue;
    }
    args.push_back(argv[i]);
  }
  int bargc = static_cast<int>(args.size());
  benchmark::Initialize(&bargc, args.data());

  auto manifest = store::parse_manifest(load::read_file(TOURMAP_MANIFEST), data_dir);
  auto cases = cases_from(manifest);
  auto tmp = std::filesystem::temp_directory_path() / ("tourmap-bench-" + std::to_string(getpid()));
  std::filesystem::create_directories(tmp);
  for (const auto& c : cases) {
    benchmark::RegisterBenchmark(("parse/" + c.file).c_str(), [&c](benchmark::State& s) { bench_parse(s, c); })
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("import/" + c.file).c_str(),
                                 [&c, dir = tmp.string()](benchmark::State& s) { bench_import(s, c, dir); })
        ->Unit(benchmark::kMillisecond);
  }
  for (const auto& r : manifest.roads)
    benchmark::RegisterBenchmark(("context/" + load::file_name(r.file)).c_str(),
                                 [file = r.file, name = load::file_name(r.file)](benchmark::State& s) {
                                   bench_context(s, file, name);
                                 })
        ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary(cases);
  std::filesystem::remove_all(tmp);
  return 0;
}
