#include "cut_tree.hpp"

#include <stdexcept>
#include <string>

namespace tourmap::crowd {

CutTree build_cut_tree(const ClusterHierarchy& h) {
  CutTree t;
  if (h.root < 0) return t;
  const std::size_t n = h.clusters.size();
  if (static_cast<std::size_t>(h.root) >= n) throw std::invalid_argument("cut tree: the root is not a cluster");
  t.nodes.reserve(n);
  t.cluster.reserve(n);
  t.triangles.reserve(n);
  std::vector<char> seen(n, 0);
  // Preorder with an explicit stack; a node's skip is set when its subtree is done, i.e. when
  // the stack pops past it (marked by pushing ~node after its children).
  std::vector<long long> stack{h.root};
  Box3 hull;
  while (!stack.empty()) {
    const long long top = stack.back();
    stack.pop_back();
    if (top < 0) {  // the subtree of node ~top is complete
      t.nodes[static_cast<std::size_t>(~top)].skip = static_cast<std::uint32_t>(t.nodes.size());
      continue;
    }
    const auto id = static_cast<std::size_t>(top);
    if (id >= n || seen[id]) throw std::invalid_argument("cut tree: cluster " + std::to_string(id) + " reached twice or missing");
    seen[id] = 1;
    const Cluster& c = h.clusters[id];
    const bool leaf = c.children[0] < 0 && c.children[1] < 0;
    if (!leaf && (c.children[0] < 0 || c.children[1] < 0))
      throw std::invalid_argument("cut tree: cluster " + std::to_string(id) + " has one child");
    const Vec3 center = c.bounds.center(), half = c.bounds.sizes() * 0.5f;
    hull.extend(c.bounds);
    CutNode node{{center.x(), center.y(), center.z()},
                 leaf ? -1.f : c.error * c.error,
                 {half.x(), half.y(), half.z()},
                 0};
    const auto index = static_cast<long long>(t.nodes.size());
    t.nodes.push_back(node);
    t.cluster.push_back(static_cast<int>(id));
    t.triangles.push_back(c.triangle_count());
    stack.push_back(~index);
    if (!leaf) {
      stack.push_back(c.children[1]);
      stack.push_back(c.children[0]);  // visited first: right after its parent
    }
  }
  t.hull_center = hull.center();
  t.hull_half = hull.sizes() * 0.5f;
  return t;
}

}  // namespace tourmap::crowd
