#include "deform/problem.hpp"

namespace tourmap::deform {

double residue(const PlanarNetwork& net, const Targets& targets, const std::vector<XY>& p) {
  double sum = 0.0;
  for (std::size_t i = 0; i < net.edges.size(); ++i) {
    auto [u, v] = net.edges[i];
    double s = targets.edge_scale.empty() ? 1.0 : targets.edge_scale[i];
    double dx = (p[u].x - p[v].x) - s * (net.nodes[u].x - net.nodes[v].x);
    double dy = (p[u].y - p[v].y) - s * (net.nodes[u].y - net.nodes[v].y);
    sum += dx * dx + dy * dy;
  }
  for (const auto& g : targets.guides) {
    double dx = p[g.node].x - g.target.x, dy = p[g.node].y - g.target.y;
    sum += dx * dx + dy * dy;
  }
  return sum;
}

}  // namespace tourmap::deform
