#include "metro/layout_graph.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace tourmap::metro {

LayoutGraph layout_graph_of(const model::MetroNetwork& net, const geo::LocalProjection& projection, double length) {
  LayoutGraph g;
  for (const auto& n : net.nodes) g.pos.push_back(geo::project(projection, n.pos));
  for (const auto& e : net.edges) {
    g.edges.push_back({e.from, e.to});
    g.edge_lines.push_back(e.lines);
    g.min_length.push_back(length);
  }
  separate_coincident(g, 15.0);
  return g;
}

std::vector<double> visual_worth_lengths(const LayoutGraph& g, const std::vector<double>& node_worth, double l_const) {
  double mean = 0;
  for (double w : node_worth) mean += w;
  mean = node_worth.empty() ? 0 : mean / node_worth.size();
  std::vector<double> out;
  out.reserve(g.edges.size());
  for (auto [u, v] : g.edges) {
    double f = mean > 0 ? (node_worth[u] + node_worth[v]) / (2 * mean) : 1.0;  // eq. 5.4
    out.push_back(l_const * std::clamp(f, 0.5, 2.5));
  }
  return out;
}

std::size_t separate_coincident(LayoutGraph& g, double gap) {
  std::map<std::pair<double, double>, std::vector<std::uint32_t>> at;
  for (std::uint32_t i = 0; i < g.pos.size(); ++i) at[{g.pos[i].x, g.pos[i].y}].push_back(i);
  std::size_t moved = 0;
  for (const auto& [p, nodes] : at) {
    if (nodes.size() < 2) continue;
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      double a = 2 * M_PI * k / nodes.size();
      g.pos[nodes[k]] = {p.first + gap * std::cos(a), p.second + gap * std::sin(a)};
      ++moved;
    }
  }
  return moved;
}

}  // namespace tourmap::metro
