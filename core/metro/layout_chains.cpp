#include "metro/layout_chains.hpp"

namespace tourmap::metro {
namespace {

std::uint32_t other_end(const LayoutGraph& g, std::uint32_t e, std::uint32_t v) {
  return g.edges[e].first == v ? g.edges[e].second : g.edges[e].first;
}

LayoutChain walk(const LayoutGraph& g, const std::vector<std::vector<std::uint32_t>>& incident,
                 const std::vector<char>& anchor, std::vector<char>& used, std::uint32_t start, std::uint32_t edge) {
  LayoutChain chain;
  chain.a = start;
  std::uint32_t at = start;
  while (true) {
    used[edge] = 1;
    chain.edges.push_back(edge);
    chain.forward.push_back(g.edges[edge].first == at ? 1 : 0);
    const std::uint32_t next = other_end(g, edge, at);
    if (anchor[next]) {
      chain.b = next;
      return chain;
    }
    chain.inner.push_back(next);
    const auto& two = incident[next];  // degree 2: the edge we came by and the one to go on
    edge = two[0] == edge ? two[1] : two[0];
    at = next;
  }
}

}  // namespace

std::vector<LayoutChain> layout_chains(const LayoutGraph& g) {
  const std::size_t n = g.pos.size();
  std::vector<std::vector<std::uint32_t>> incident(n);
  for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
    incident[g.edges[e].first].push_back(e);
    incident[g.edges[e].second].push_back(e);
  }
  std::vector<char> anchor(n), used(g.edges.size());
  for (std::size_t v = 0; v < n; ++v) anchor[v] = incident[v].size() != 2 || incident[v][0] == incident[v][1];
  std::vector<LayoutChain> chains;
  for (std::uint32_t v = 0; v < n; ++v)
    if (anchor[v])
      for (auto e : incident[v])
        if (!used[e]) chains.push_back(walk(g, incident, anchor, used, v, e));
  for (std::uint32_t e = 0; e < g.edges.size(); ++e)  // what is left are pure cycles
    if (!used[e]) {
      const std::uint32_t v = g.edges[e].first;
      anchor[v] = 1;
      chains.push_back(walk(g, incident, anchor, used, v, e));
    }
  return chains;
}

std::vector<XY> chain_polyline(const LayoutChain& chain, const Layout& layout) {
  std::vector<XY> pts;
  for (std::size_t i = 0; i < chain.edges.size(); ++i) {
    const auto& path = layout.paths[chain.edges[i]];
    const std::size_t m = path.size();
    for (std::size_t k = 0; k < m; ++k) {
      if (i > 0 && k == 0) continue;  // the joint, already there
      pts.push_back(chain.forward[i] ? path[k] : path[m - 1 - k]);
    }
  }
  return pts;
}

}  // namespace tourmap::metro
