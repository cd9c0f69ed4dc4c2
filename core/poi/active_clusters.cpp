#include "poi/active_clusters.hpp"

#include <algorithm>

namespace tourmap::poi {

bool is_active(const ClusterNode& c, geo::XY lo, geo::XY hi) {
  const double window_side = std::min(hi.x - lo.x, hi.y - lo.y);
  const double side = std::max(c.max.x - c.min.x, c.max.y - c.min.y);
  return c.min.x >= lo.x && c.min.y >= lo.y && c.max.x <= hi.x && c.max.y <= hi.y && side < window_side;
}

namespace {

double side_of(const ClusterNode& c) { return std::max(c.max.x - c.min.x, c.max.y - c.min.y); }

// Splits the largest splittable cluster until there are `at_least` (see the header).
void refine(const ClusterTree& tree, std::vector<std::uint32_t>& found, std::size_t at_least) {
  auto smaller = [&](std::uint32_t a, std::uint32_t b) {
    const double sa = side_of(tree.nodes[a]), sb = side_of(tree.nodes[b]);
    return sa < sb || (sa == sb && a > b);
  };
  std::vector<std::uint32_t> unsplittable, heap;  // heap: clusters that can still split
  for (std::uint32_t id : found) (tree.nodes[id].child_count > 0 ? heap : unsplittable).push_back(id);
  std::make_heap(heap.begin(), heap.end(), smaller);
  while (!heap.empty() && unsplittable.size() + heap.size() < at_least) {
    std::pop_heap(heap.begin(), heap.end(), smaller);
    const ClusterNode& c = tree.nodes[heap.back()];
    heap.pop_back();
    for (std::uint32_t a = 0; a < c.child_count; ++a) {
      const std::uint32_t child = tree.children[c.first_child + a];
      if (tree.nodes[child].child_count == 0) {
        unsplittable.push_back(child);
      } else {
        heap.push_back(child);
        std::push_heap(heap.begin(), heap.end(), smaller);
      }
    }
  }
  found = std::move(unsplittable);
  found.insert(found.end(), heap.begin(), heap.end());
}

}  // namespace

ActiveClusters active_clusters(const ClusterTree& tree, geo::XY lo, geo::XY hi, std::size_t m, std::size_t at_least) {
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
  if (found.size() < at_least) {
    refine(tree, found, at_least);
    total = 0;
    for (std::uint32_t id : found) total += tree.nodes[id].worth;
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
