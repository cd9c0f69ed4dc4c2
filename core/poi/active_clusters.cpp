#include "poi/active_clusters.hpp"

#include <algorithm>

namespace tourmap::poi {

bool is_active(const ClusterNode& c, geo::XY lo, geo::XY hi) {
  const double window_side = std::min(hi.x - lo.x, hi.y - lo.y);
  const double side = std::max(c.max.x - c.min.x, c.max.y - c.min.y);
  return c.min.x >= lo.x && c.min.y >= lo.y && c.max.x <= hi.x && c.max.y <= hi.y && side < window_side;
}

ActiveClusters active_clusters(const ClusterTree& tree, geo::XY lo, geo::XY hi, std::size_t m) {
  ActiveClusters out;
  if (tree.nodes.empty() || !(lo.x <= hi.x && lo.y <= hi.y)) return out;

  // Depth-first; a subtree whose bbox misses the window holds no active cluster.
  std::vector<std::uint32_t> found, stack{tree.root};
  double total = 0;
  while (!stack.empty()) {
    const std::uint32_t id = stack.back();
    stack.pop_back();
    const ClusterNode& c = tree.nodes[id];
    if (c.max.x < lo.x || c.min.x > hi.x || c.max.y < lo.y || c.min.y > hi.y) continue;
    if (is_active(c, lo, hi)) {
      found.push_back(id);
      total += c.worth;
      continue;
    }
    for (std::uint32_t a = 0; a < c.child_count; ++a) stack.push_back(tree.children[c.first_child + a]);
  }
  out.active = found.size();

  auto before = [&](std::uint32_t a, std::uint32_t b) {
    const double wa = tree.nodes[a].worth, wb = tree.nodes[b].worth;
    return wa > wb || (wa == wb && a < b);
  };
  const std::size_t shown = std::min(found.size(), 2 * m);
  std::partial_sort(found.begin(), found.begin() + static_cast<std::ptrdiff_t>(shown), found.end(), before);
  const std::size_t top = std::min(shown, m);
  out.top.assign(found.begin(), found.begin() + static_cast<std::ptrdiff_t>(top));
  out.previews.assign(found.begin() + static_cast<std::ptrdiff_t>(top),
                      found.begin() + static_cast<std::ptrdiff_t>(shown));
  for (std::size_t i = 0; i < shown; ++i)
    out.prominence.push_back(total > 0 ? tree.nodes[found[i]].worth / total : 1.0 / static_cast<double>(found.size()));
  return out;
}

}  // namespace tourmap::poi
