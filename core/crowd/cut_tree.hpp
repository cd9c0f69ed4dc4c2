#pragma once
// A cluster hierarchy flattened for the runtime LOD cut (sec. 3.5.1): one 32-byte node per
// cluster in depth-first order (the first child right after its parent), with the cluster's
// model-space box as centre/half-extent, its squared error radius and the index just past its
// subtree. A cut walks it front to back without a stack: descend = next node, skip a culled or
// drawn subtree = jump to `skip`. Built once per hierarchy; read-only afterwards.

#include "cluster_hierarchy.hpp"

#include <cstdint>
#include <vector>

namespace tourmap::crowd {

struct CutNode {
  float center[3];
  float error_sq;      // (error radius)^2 in model units; -1 at a leaf (always fine enough)
  float half[3];       // half-extent of the cluster's box
  std::uint32_t skip;  // index of the first node after this subtree
};
static_assert(sizeof(CutNode) == 32);

struct CutTree {
  std::vector<CutNode> nodes;             // depth-first order, nodes[0] is the root
  std::vector<int> cluster;               // node -> cluster id in the hierarchy
  std::vector<std::uint32_t> triangles;   // node -> triangles of that cluster
  // A box holding every node's box (their union's bounds). Not the root's box: a child may stick
  // out of its parent (a parent's vertices are a subset of its children's; build_hierarchy widens
  // parents over their children, but nothing else enforces it), so only this box bounds the whole
  // hierarchy for the per-instance culled / wholly-inside tests.
  Vec3 hull_center = Vec3::Zero(), hull_half = Vec3::Constant(-1);
};

// Throws std::invalid_argument when `h` is not a binary tree reachable from its root (a leaf has
// no children, an inner cluster two distinct ones, no cluster is reached twice).
CutTree build_cut_tree(const ClusterHierarchy& h);

}  // namespace tourmap::crowd
