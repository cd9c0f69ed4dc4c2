#include "metro/grid_chains.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace tourmap::metro::octi {
namespace {

using Incidence = std::vector<std::vector<std::uint32_t>>;  // per node: its edges

Incidence incident_edges(const LayoutGraph& g) {
  Incidence incident(g.pos.size());
  for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
    incident[g.edges[e].first].push_back(e);
    incident[g.edges[e].second].push_back(e);
  }
  return incident;
}

std::uint32_t other_end(const LayoutGraph& g, std::uint32_t e, std::uint32_t v) {
  return g.edges[e].first == v ? g.edges[e].second : g.edges[e].first;
}

// A node that cannot be inside a chain: not of degree 2, two edges with different lines, or
// two edges to the same neighbour.
bool ends_chains(const LayoutGraph& g, const Incidence& incident, std::uint32_t v) {
  const auto& inc = incident[v];
  return inc.size() != 2 || sorted_lines(g.edge_lines[inc[0]]) != sorted_lines(g.edge_lines[inc[1]]) ||
         other_end(g, inc[0], v) == other_end(g, inc[1], v);
}

// Walks chains from anchors along not yet walked edges.
class ChainWalk {
 public:
  ChainWalk(const LayoutGraph& g, const Incidence& incident, const std::vector<bool>& anchor)
      : g_(g), incident_(incident), anchor_(anchor), done_(g.edges.size(), false) {}

  // Every chain from every anchor, anchors in index order.
  void walk_all(std::vector<Chain>& chains) {
    for (std::uint32_t a = 0; a < incident_.size(); ++a)
      if (anchor_[a])
        for (auto e : incident_[a])
          if (!done_[e]) chains.push_back(walk(a, e));
  }

  bool walked(std::uint32_t e) const { return done_[e]; }

 private:
  // The chain from anchor a along edge e0 to the next anchor.
  Chain walk(std::uint32_t a, std::uint32_t e0) {
    Chain c;
    c.nodes.push_back(a);
    c.lines = sorted_lines(g_.edge_lines[e0]);
    std::uint32_t v = a, e = e0;
    while (true) {
      done_[e] = true;
      c.edges.push_back(e);
      c.forward.push_back(g_.edges[e].first == v);
      v = other_end(g_, e, v);
      c.nodes.push_back(v);
      if (anchor_[v]) break;
      e = incident_[v][0] == e ? incident_[v][1] : incident_[v][0];
    }
    return c;
  }

  const LayoutGraph& g_;
  const Incidence& incident_;
  const std::vector<bool>& anchor_;
  std::vector<bool> done_;  // by edge: in a chain
};

// A chain that returns to its own anchor, split at its middle node (which becomes an anchor).
std::pair<Chain, Chain> split_at_middle(const Chain& c, std::vector<bool>& anchor) {
  std::size_t mid = c.nodes.size() / 2;
  anchor[c.nodes[mid]] = true;
  Chain first, second;
  first.lines = second.lines = c.lines;
  first.nodes.assign(c.nodes.begin(), c.nodes.begin() + mid + 1);
  second.nodes.assign(c.nodes.begin() + mid, c.nodes.end());
  first.edges.assign(c.edges.begin(), c.edges.begin() + mid);
  second.edges.assign(c.edges.begin() + mid, c.edges.end());
  first.forward.assign(c.forward.begin(), c.forward.begin() + mid);
  second.forward.assign(c.forward.begin() + mid, c.forward.end());
  return {std::move(first), std::move(second)};
}

}  // namespace

std::vector<std::uint32_t> sorted_lines(std::vector<std::uint32_t> l) {
  std::sort(l.begin(), l.end());
  l.erase(std::unique(l.begin(), l.end()), l.end());
  return l;
}

std::vector<Chain> contract_chains(const LayoutGraph& g, std::vector<bool>& anchor) {
  const std::size_t n = g.pos.size();
  const auto incident = incident_edges(g);
  anchor.resize(n, false);
  for (std::uint32_t v = 0; v < n; ++v) anchor[v] = anchor[v] || ends_chains(g, incident, v);
  std::vector<Chain> chains;
  ChainWalk walk(g, incident, anchor);
  walk.walk_all(chains);
  // Cycles of degree-2 nodes: anchor one node per cycle and walk again.
  for (std::uint32_t e = 0; e < g.edges.size(); ++e)
    if (!walk.walked(e)) {
      anchor[g.edges[e].first] = true;
      walk.walk_all(chains);
    }
  // A chain that returns to its own anchor is split at its middle node.
  std::vector<Chain> out;
  for (auto& c : chains) {
    if (c.nodes.front() != c.nodes.back() || c.nodes.size() < 3) {
      out.push_back(std::move(c));
      continue;
    }
    auto [first, second] = split_at_middle(c, anchor);
    out.push_back(std::move(first));
    out.push_back(std::move(second));
  }
  return out;
}

double end_angle(const LayoutGraph& g, const Chain& c, bool from_front) {
  std::uint32_t a = from_front ? c.nodes[0] : c.nodes.back();
  std::uint32_t b = from_front ? c.nodes[1] : c.nodes[c.nodes.size() - 2];
  return std::atan2(g.pos[b].y - g.pos[a].y, g.pos[b].x - g.pos[a].x);
}

std::vector<double> node_shares(const LayoutGraph& g, const Chain& c) {
  double total = 0;
  for (auto e : c.edges) total += g.min_length[e];
  double run = 0;
  std::vector<double> t{0.0};
  for (auto e : c.edges) {
    run += g.min_length[e];
    t.push_back(total > 0 ? run / total : double(t.size()) / c.edges.size());
  }
  return t;
}

void unroll_chain(const LayoutGraph& g, const Chain& c, const std::vector<XY>& path, Layout& layout) {
  const auto t = node_shares(g, c);
  for (std::size_t k = 1; k + 1 < c.nodes.size(); ++k) layout.pos[c.nodes[k]] = point_along(path, t[k]);
  for (std::size_t k = 0; k < c.edges.size(); ++k) {
    auto piece = simplify_collinear(sub_polyline(path, t[k], t[k + 1]));
    if (!c.forward[k]) std::reverse(piece.begin(), piece.end());
    layout.paths[c.edges[k]] = std::move(piece);
  }
}

XY point_along(const std::vector<XY>& line, double t) {
  if (t <= 0) return line.front();
  if (t >= 1) return line.back();
  double total = 0;
  for (std::size_t i = 1; i < line.size(); ++i) total += std::hypot(line[i].x - line[i - 1].x, line[i].y - line[i - 1].y);
  double want = t * total, run = 0;
  for (std::size_t i = 1; i < line.size(); ++i) {
    double seg = std::hypot(line[i].x - line[i - 1].x, line[i].y - line[i - 1].y);
    if (run + seg >= want && seg > 0) {
      double f = (want - run) / seg;
      return {line[i - 1].x + f * (line[i].x - line[i - 1].x), line[i - 1].y + f * (line[i].y - line[i - 1].y)};
    }
    run += seg;
  }
  return line.back();
}

std::vector<XY> sub_polyline(const std::vector<XY>& line, double t0, double t1) {
  double total = 0;
  std::vector<double> at(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i) {
    total += std::hypot(line[i].x - line[i - 1].x, line[i].y - line[i - 1].y);
    at[i] = total;
  }
  std::vector<XY> out{point_along(line, t0)};
  for (std::size_t i = 1; i + 1 < line.size(); ++i)
    if (at[i] > t0 * total + 1e-12 && at[i] < t1 * total - 1e-12) out.push_back(line[i]);
  out.push_back(point_along(line, t1));
  return out;
}

std::vector<XY> simplify_collinear(const std::vector<XY>& line) {
  if (line.size() <= 2) return line;
  std::vector<XY> out{line.front()};
  for (std::size_t i = 1; i + 1 < line.size(); ++i) {
    const auto& a = out.back();
    const auto& b = line[i];
    const auto& c = line[i + 1];
    double cross = (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x);
    double scale = std::hypot(b.x - a.x, b.y - a.y) * std::hypot(c.x - b.x, c.y - b.y);
    if (std::abs(cross) > 1e-9 * std::max(scale, 1e-12)) out.push_back(b);
  }
  out.push_back(line.back());
  return out;
}

}  // namespace tourmap::metro::octi
