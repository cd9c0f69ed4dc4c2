#pragma once
// Layout graphs of shared metro networks (../shared/data), every edge 10 units long.

#include "geo/projection.hpp"
#include "load/metro_load.hpp"
#include "metro/layout_graph.hpp"
#include "test_data.hpp"

namespace tourmap::metro::test_networks {

// A small hand-made network: one line on every edge, every edge `length` long.
inline LayoutGraph graph(std::vector<XY> pos, std::vector<std::pair<std::uint32_t, std::uint32_t>> edges,
                         double length = 10) {
  LayoutGraph g;
  g.pos = std::move(pos);
  g.edges = std::move(edges);
  g.edge_lines.assign(g.edges.size(), {0});
  g.min_length.assign(g.edges.size(), length);
  return g;
}

inline LayoutGraph graph_of(const model::MetroNetwork& net) {
  return layout_graph_of(net, geo::projection_for(model::bbox_of(net)));
}

inline LayoutGraph vienna() { return graph_of(load::load_metro_loom(test::data_file("metro/loom_wien.json"))); }

// The largest shared network: 302 stations, lines that cross without shared stations.
inline LayoutGraph london() {
  return graph_of(load::load_metro_station_csvs(test::data_file("metro/london.stations.csv"),
                                                test::data_file("metro/london.lines.csv"),
                                                test::data_file("metro/london.connections.csv")));
}

}  // namespace tourmap::metro::test_networks
