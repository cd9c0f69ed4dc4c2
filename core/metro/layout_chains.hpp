#pragma once
// The chains of a drawn metro network: maximal paths through nodes of degree 2 between two
// anchors (nodes of any other degree). A reader follows a line from interchange to interchange,
// so bends are counted along chains (as ../shared/tools/metro_compare.py does); a bend where
// lines meet at an interchange is not one. A component that is a pure cycle gets one of its
// nodes as an anchor (its chain starts and ends there).

#include "metro/layout_graph.hpp"

#include <cstdint>
#include <vector>

namespace tourmap::metro {

struct LayoutChain {
  std::uint32_t a = 0, b = 0;            // anchors (a == b for a cycle)
  std::vector<std::uint32_t> edges;      // in order from a to b
  std::vector<char> forward;             // per edge: runs from a's side (first -> second)
  std::vector<std::uint32_t> inner;      // the degree-2 nodes in order, inner.size() == edges.size() - 1
};

std::vector<LayoutChain> layout_chains(const LayoutGraph& g);

// The chain drawn as one polyline from a to b (the edges' paths joined).
std::vector<XY> chain_polyline(const LayoutChain& chain, const Layout& layout);

}  // namespace tourmap::metro
