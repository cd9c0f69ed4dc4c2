// The walk from the station (issue 17, part 4): for the whole-city extracts of the sample data,
// the walking graph's build time (walk/walk_graph.hpp, once per road network version in the
// server) and the time of one nearest-stations search (walk/station_walk.hpp) per POI, as
// GET /cities/{id}/pois/{poi}/walk runs it, over every POI of the city, p50/p99/max, for the
// default parameters and the largest ones (5 stations, 5 km). The baseline, measured in the same
// run: one plain Boost.Graph Dijkstra over the whole walking graph from the POI's vertex (what
// the search costs without its stop at k stations / max_m); `speed-up` is its p50 over ours.
//
//   build/bench/walk_bench [--data-dir DIR] [--runs N]

#include "load/metro_osm.hpp"
#include "load/osm_pois.hpp"
#include "load/osm_roads.hpp"
#include "walk/station_walk.hpp"

#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <boost/property_map/function_property_map.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace {

using namespace tourmap;
using Clock = std::chrono::steady_clock;

struct Extract {
  std::string id, file;
  std::vector<std::string> modes;  // as in scripts/sample-data.json
};

double ms(Clock::time_point since) { return std::chrono::duration<double, std::milli>(Clock::now() - since).count(); }

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

// The baseline: the whole graph's distances from the POI's road vertex (no early stop).
double full_dijkstra_ms(const walk::WalkGraph& g, geo::LonLat from) {
  const auto t = Clock::now();
  const auto snap = walk::snap_to_road(g, from);
  if (!snap.found) return ms(t);
  std::vector<double> dist(g.vertex_count());
  std::vector<std::uint32_t> pred(g.vertex_count());
  boost::dijkstra_shortest_paths(
      g.graph, snap.vertex,
      boost::weight_map(boost::get(&walk::WalkEdgeLength::metres, g.graph))
          .distance_map(boost::make_iterator_property_map(dist.begin(), boost::get(boost::vertex_index, g.graph)))
          .predecessor_map(boost::make_iterator_property_map(pred.begin(), boost::get(boost::vertex_index, g.graph))));
  return ms(t);
}

}  // namespace

int main(int argc, char** argv) {
  std::string data_dir = TOURMAP_DEFAULT_DATA_DIR;
  int runs = 20;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--data-dir")) data_dir = argv[i + 1];
    else if (!std::strcmp(argv[i], "--runs")) runs = std::max(1, std::atoi(argv[i + 1]));
  }
  const std::vector<Extract> extracts = {{"liechtenstein", data_dir + "/roads/liechtenstein-latest.osm.pbf", {"train", "bus"}},
                                         {"monaco", data_dir + "/roads/monaco.osm.gz", {}}};
  std::printf("# Walking from a POI to its nearest stations (best build of %d; every POI searched %d times)\n\n", runs,
              runs);
  std::printf("| city | road edges | walk vertices | walk edges | snap vertices | build ms | graph MB | stations | POIs |\n"
              "|---|---|---|---|---|---|---|---|---|\n");
  struct Loaded {
    std::shared_ptr<const walk::WalkGraph> graph;
    std::vector<walk::WalkTarget> stations;
    std::vector<model::Poi> pois;
  };
  std::map<std::string, Loaded> loaded;
  for (const auto& e : extracts) {
    const auto roads = load::load_osm_roads(e.file);
    const auto metro = load::load_metro_osm(e.file, e.modes);
    Loaded l;
    l.pois = load::load_osm_pois(e.file);
    std::map<std::string, std::uint32_t> groups;
    for (const auto& n : metro.nodes)
      if (n.is_station())
        l.stations.push_back({n.pos, groups.try_emplace(n.station_id, static_cast<std::uint32_t>(groups.size())).first->second});
    double best = 1e30;
    for (int r = 0; r < runs; ++r) {
      const auto t = Clock::now();
      l.graph = walk::build_walk_graph(roads);
      best = std::min(best, ms(t));
    }
    std::printf("| %s | %zu | %zu | %zu | %zu | %.1f | %.1f | %zu | %zu |\n", e.id.c_str(), roads.edges.size(),
                l.graph->vertex_count(), l.graph->edge_count(), l.graph->snap_vertices, best,
                static_cast<double>(l.graph->bytes()) / (1 << 20), groups.size(), l.pois.size());
    loaded.emplace(e.id, std::move(l));
  }

  std::printf("\nOne search per POI (ms; settled: vertices the search settled):\n\n"
              "| city | stations | max_m | searches | p50 ms | p99 ms | max ms | settled p50 | settled max | walks found | "
              "full Dijkstra p50 ms | speed-up |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& e : extracts) {
    const auto& l = loaded.at(e.id);
    for (const auto& [k, max_m] : std::vector<std::pair<std::size_t, double>>{{3, 2000}, {5, 5000}}) {
      std::vector<double> times, settled, full;
      std::size_t walks = 0;
      for (int r = 0; r < runs; ++r)
        for (const auto& p : l.pois) {
          walk::WalkQuery q;
          q.from = p.pos;
          q.targets = l.stations;
          q.k = k;
          q.max_m = max_m;
          const auto t = Clock::now();
          const auto result = walk::nearest_walks(*l.graph, q);
          times.push_back(ms(t));
          full.push_back(full_dijkstra_ms(*l.graph, p.pos));
          if (r == 0) {
            settled.push_back(static_cast<double>(result.settled));
            walks += result.walks.size();
          }
        }
      const double p50 = quantile(times, 0.5), full_p50 = quantile(full, 0.5);
      std::printf("| %s | %zu | %.0f | %zu | %.3f | %.3f | %.3f | %.0f | %.0f | %zu | %.3f | %.0fx |\n", e.id.c_str(), k,
                  max_m, times.size(), p50, quantile(times, 0.99), quantile(times, 1.0), quantile(settled, 0.5),
                  quantile(settled, 1.0), walks, full_p50, p50 > 0 ? full_p50 / p50 : 0.0);
    }
  }
  return 0;
}
