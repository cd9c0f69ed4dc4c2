#include "metro/octilinear_grid.hpp"

#include "metro/layout_quality.hpp"
#include "util/stop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <deque>
#include <iterator>
#include <queue>
#include <tuple>

namespace tourmap::metro {
namespace {

using Clock = std::chrono::steady_clock;

// Directions, counter-clockwise from east: 0 E, 1 NE, 2 N, 3 NW, 4 W, 5 SW, 6 S, 7 SE.
constexpr int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr int kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kNoDir = 8;

int turn(int a, int b) {
  int d = std::abs(a - b) % 8;
  return std::min(d, 8 - d);
}

// ---- contraction of degree-2 chains -------------------------------------------------------

struct Chain {
  std::vector<std::uint32_t> nodes;  // anchor, interior..., anchor
  std::vector<std::uint32_t> edges;  // original edges along it
  std::vector<bool> forward;         // edge runs in chain direction
  std::vector<std::uint32_t> lines;  // sorted line set
};

std::vector<std::uint32_t> sorted_lines(std::vector<std::uint32_t> l) {
  std::sort(l.begin(), l.end());
  l.erase(std::unique(l.begin(), l.end()), l.end());
  return l;
}

// `anchor` comes in with the nodes that must stay chain ends and goes out with all of them.
std::vector<Chain> contract(const LayoutGraph& g, std::vector<bool>& anchor) {
  std::size_t n = g.pos.size();
  std::vector<std::vector<std::uint32_t>> incident(n);
  for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
    incident[g.edges[e].first].push_back(e);
    incident[g.edges[e].second].push_back(e);
  }
  auto other = [&](std::uint32_t e, std::uint32_t v) { return g.edges[e].first == v ? g.edges[e].second : g.edges[e].first; };
  anchor.resize(n, false);
  for (std::uint32_t v = 0; v < n; ++v) {
    const auto& inc = incident[v];
    anchor[v] = anchor[v] || inc.size() != 2 || sorted_lines(g.edge_lines[inc[0]]) != sorted_lines(g.edge_lines[inc[1]]) ||
                other(inc[0], v) == other(inc[1], v);
  }
  std::vector<bool> done(g.edges.size(), false);
  std::vector<Chain> chains;
  auto walk = [&](std::uint32_t a, std::uint32_t e0) {
    Chain c;
    c.nodes.push_back(a);
    c.lines = sorted_lines(g.edge_lines[e0]);
    std::uint32_t v = a, e = e0;
    while (true) {
      done[e] = true;
      c.edges.push_back(e);
      c.forward.push_back(g.edges[e].first == v);
      v = other(e, v);
      c.nodes.push_back(v);
      if (anchor[v]) break;
      e = incident[v][0] == e ? incident[v][1] : incident[v][0];
    }
    return c;
  };
  auto walk_all = [&] {
    for (std::uint32_t a = 0; a < n; ++a)
      if (anchor[a])
        for (auto e : incident[a])
          if (!done[e]) chains.push_back(walk(a, e));
  };
  walk_all();
  // Cycles of degree-2 nodes: anchor one node per cycle and walk again.
  for (std::uint32_t e = 0; e < g.edges.size(); ++e)
    if (!done[e]) {
      anchor[g.edges[e].first] = true;
      walk_all();
    }
  // A chain that returns to its own anchor is split at its middle node.
  std::vector<Chain> out;
  for (auto& c : chains) {
    if (c.nodes.front() != c.nodes.back() || c.nodes.size() < 3) {
      out.push_back(std::move(c));
      continue;
    }
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
    out.push_back(std::move(first));
    out.push_back(std::move(second));
  }
  return out;
}

// ---- the grid and the search ------------------------------------------------------------------

struct GridGraph {
  int w = 0, h = 0;
  XY origin;
  double cell = 1;
  std::vector<std::uint8_t> used;      // 0 free, 1 path, 2 station, 3 two paths crossing
  std::vector<std::uint8_t> diagonal;  // bit d: the diagonal move in direction d from here is taken
  std::vector<int> reserved_for;       // the station next to this node (its ports need the room), or -1
  std::vector<int> owner;              // the chain whose path runs through this node, or -1
  std::vector<std::int8_t> axis;       // direction % 4 of that path when it goes straight through, else -1
  std::vector<int> owner2;             // at a crossing: the second path...
  std::vector<std::int8_t> axis2;      // ...and its axis
  std::vector<int> diagonal_owner;     // 2 per node: the chain on the NE and the NW diagonal from it

  void resize(std::size_t nodes) {
    used.assign(nodes, 0);
    diagonal.assign(nodes, 0);
    reserved_for.assign(nodes, -1);
    owner.assign(nodes, -1);
    axis.assign(nodes, -1);
    owner2.assign(nodes, -1);
    axis2.assign(nodes, -1);
    diagonal_owner.assign(2 * nodes, -1);
  }

  int at(int x, int y) const { return y * w + x; }
  XY point(int node) const { return {origin.x + (node % w) * cell, origin.y + (node / w) * cell}; }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h; }
  // Where the owner of the diagonal from `node` in direction d (odd) is kept: NE and NW
  // diagonals at their lower end, SW and SE ones as the NE / NW diagonal they reverse.
  std::size_t diagonal_slot(int node, int d) const {
    int x = node % w, y = node / w;
    if (d == 1) return 2 * static_cast<std::size_t>(node);
    if (d == 3) return 2 * static_cast<std::size_t>(node) + 1;
    if (d == 5) return 2 * static_cast<std::size_t>(at(x - 1, y - 1));
    return 2 * static_cast<std::size_t>(at(x + 1, y - 1)) + 1;
  }
  // The diagonal from `node` in direction d crosses the other diagonal of the same cell: the
  // chain on that one, or -1 when it is free.
  int crossing_diagonal(int node, int d) const {
    if (d % 2 == 0) return -1;
    int x = node % w, y = node / w;
    // Cell corners: the crossing diagonal starts at (x + dx, y) going (-dx, dy).
    int cx = x + kDx[d], cy = y;
    if (!inside(cx, cy)) return -1;
    int cross = (d == 1) ? 3 : (d == 3) ? 1 : (d == 5) ? 7 : 5;
    if (!((diagonal[at(cx, cy)] >> cross) & 1)) return -1;
    return diagonal_owner[diagonal_slot(at(cx, cy), cross)];
  }
  bool crossing_taken(int node, int d) const { return crossing_diagonal(node, d) >= 0; }
  void take_diagonal(int node, int d, int chain) {
    if (d % 2 == 0) return;
    int x = node % w, y = node / w;
    diagonal[node] |= 1 << d;
    diagonal[at(x + kDx[d], y + kDy[d])] |= 1 << ((d + 4) % 8);
    diagonal_owner[diagonal_slot(node, d)] = chain;
  }
  void release_diagonal(int node, int d) {
    if (d % 2 == 0) return;
    int x = node % w, y = node / w;
    diagonal[node] &= static_cast<std::uint8_t>(~(1 << d));
    diagonal[at(x + kDx[d], y + kDy[d])] &= static_cast<std::uint8_t>(~(1 << ((d + 4) % 8)));
    diagonal_owner[diagonal_slot(node, d)] = -1;
  }
};

struct Endpoint {
  int station = -1;  // the anchor this end belongs to
  // Candidate grid nodes with their cost, and the ports allowed / their cost at each.
  std::vector<std::pair<int, double>> nodes;
  std::array<bool, 8> allowed{};
  std::array<double, 8> port_cost{};
  XY centre;      // in cells
  double radius;  // in cells, for the heuristic
};

// A search over (node, direction) states may pass a grid node twice (a small loop can cost
// less than a sharp turn), and the path would cross itself: the loop is cut out. A cut
// cannot leave a reversal: that would need the node before the loop twice, also cut.
std::vector<int> without_loops(const std::vector<int>& path) {
  std::vector<int> out;
  for (int node : path) {
    auto again = std::find(out.begin(), out.end(), node);
    if (again != out.end()) {
      out.erase(again + 1, out.end());
      continue;
    }
    out.push_back(node);
  }
  return out;
}

class Router {
 public:
  Router(GridGraph& grid, const GridRouteParams& p) : grid_(grid), p_(p) {
    std::size_t states = static_cast<std::size_t>(grid.w) * grid.h * 9;
    cost_.assign(states, kInf);
    parent_.assign(states, -1);
    stamp_.assign(states, 0);
    target_cost_.assign(static_cast<std::size_t>(grid.w) * grid.h, kInf);
  }

  // Cheapest path from `src` to `dst`; empty when there is none. Grid node sequence.
  std::vector<int> route(const Endpoint& src, const Endpoint& dst) {
    ++now_;
    corridor_a_ = {static_cast<double>(src.nodes.front().first % grid_.w), static_cast<double>(src.nodes.front().first / grid_.w)};
    corridor_b_ = dst.centre;
    corridor_slack_ = std::max(p_.corridor_slack,
                               p_.corridor_share * std::hypot(corridor_b_.x - corridor_a_.x, corridor_b_.y - corridor_a_.y));
    for (const auto& [node, c] : dst.nodes) target_cost_[node] = c;
    auto h = [&](int node) {
      double dx = std::abs(node % grid_.w - dst.centre.x), dy = std::abs(node / grid_.w - dst.centre.y);
      double oct = std::max(dx, dy) + (std::sqrt(2.0) - 1) * std::min(dx, dy);
      return std::max(0.0, oct - dst.radius * std::sqrt(2.0));
    };
    using Item = std::pair<double, long>;  // f, state (>= goal_base: goal)
    std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
    const long goal_base = static_cast<long>(cost_.size());
    std::vector<double> goal_cost;  // by state, lazily
    auto set = [&](long s, double c, long parent) {
      if (stamp_[s] != now_ || c < cost_[s]) {
        stamp_[s] = now_;
        cost_[s] = c;
        parent_[s] = parent;
        return true;
      }
      return false;
    };
    for (const auto& [node, c] : src.nodes) {
      long s = static_cast<long>(node) * 9 + kNoDir;
      if (set(s, c, -1)) open.push({c + h(node), s});
    }
    long found = -1;
    double best_goal = kInf;
    std::size_t expansions = 0;
    // Long routes may explore more; hopeless ones still stop.
    double reach = h(src.nodes.front().first) + 10;
    std::size_t cap = std::min<std::size_t>(p_.max_expansions * 8,
                                            std::max<std::size_t>(p_.max_expansions, 60 * reach * reach));
    while (!open.empty()) {
      if (++expansions > cap) break;
      auto [f, s] = open.top();
      open.pop();
      if (s >= goal_base) {
        found = s - goal_base;
        break;
      }
      if (f > best_goal) break;
      int node = static_cast<int>(s / 9), din = static_cast<int>(s % 9);
      double c = cost_[s];
      if (stamp_[s] != now_ || f - h(node) > c + 1e-9) continue;  // stale
      int x = node % grid_.w, y = node / grid_.w;
      // Crossing another path here: straight on only. (Negotiating, the search may also
      // have come through to tear that path up: then it may turn.)
      const bool crossing_here = !overlap_ && din != kNoDir && grid_.used[node] != 0 &&
                                 (!negotiate_ || (grid_.used[node] == 1 && grid_.axis[node] >= 0 &&
                                                  grid_.axis[node] != din % 4 && crossing_price(grid_.owner[node]) < kInf));
      for (int d = 0; d < 8; ++d) {
        if (crossing_here && d != din) continue;
        double step = c;
        if (din == kNoDir) {
          if (!src.allowed[d]) continue;
          step += src.port_cost[d];
        } else {
          int t = turn(din, d);
          if (t == 4) continue;
          step += p_.bend_cost[t];
        }
        int nx = x + kDx[d], ny = y + kDy[d];
        if (!grid_.inside(nx, ny)) continue;
        int next = grid_.at(nx, ny);
        if (int other = grid_.crossing_diagonal(node, d); other >= 0) {
          double price = crossing_price(other);
          if (price == kInf) {
            if (negotiate_) price = eviction_price(node);
            else if (overlap_) price = p_.overlap_cost;
            else continue;
          }
          step += price;
        }
        step += (d % 2) ? std::sqrt(2.0) : 1.0;
        double tc = target_cost_[next];
        if (tc < kInf) {
          int port = (d + 4) % 8;
          if (dst.allowed[port]) {
            double total = step + tc + dst.port_cost[port];
            long gs = static_cast<long>(next) * 9 + d;
            best_goal = std::min(best_goal, total);
            open.push({total, goal_base + gs});
            goal_parents_.push_back({gs, s, total});
          }
        }
        if (grid_.used[next] != 0) {
          // A path going straight through `next` on another axis may be crossed there.
          double price = grid_.used[next] == 1 && grid_.axis[next] >= 0 && grid_.axis[next] != d % 4
                             ? crossing_price(grid_.owner[next])
                             : kInf;
          if (price == kInf) {
            if (grid_.used[next] == 2) continue;  // a station
            if (negotiate_) price = eviction_price(next) * (grid_.used[next] == 3 ? 2 : 1);
            else if (overlap_) price = p_.overlap_cost;
            else continue;
          }
          step += price;
        }
        int owner = grid_.reserved_for[next];
        if (owner >= 0 && owner != src.station && owner != dst.station) step += p_.reserved_penalty;
        // Stay near the straight corridor between the ends: long detours wall in other stations.
        if (p_.corridor_cost > 0) {
          double off = distance_to_segment(nx, ny, corridor_a_, corridor_b_);
          if (off > corridor_slack_) step += p_.corridor_cost * (off - corridor_slack_);
        }
        long ns = static_cast<long>(next) * 9 + d;
        if (set(ns, step, s)) open.push({step + h(next), ns});
      }
    }
    for (const auto& [node, c] : dst.nodes) target_cost_[node] = kInf;
    std::vector<int> path;
    if (found < 0) {
      goal_parents_.clear();
      return path;
    }
    // The goal state's parent is its cheapest recorded arrival.
    long parent = -1;
    double best = kInf;
    for (const auto& arrival : goal_parents_)
      if (arrival.goal == found && arrival.total < best) {
        best = arrival.total;
        parent = arrival.parent;
      }
    goal_parents_.clear();
    path.push_back(static_cast<int>(found / 9));
    for (long s = parent; s >= 0; s = parent_[s]) path.push_back(static_cast<int>(s / 9));
    std::reverse(path.begin(), path.end());
    return without_loops(path);
  }

 // Last resort for a walled-in chain: pass through other paths at a high cost, so the edge
 // stays octilinear (the crossing is reported by the quality check).
 void allow_overlap(bool on) { overlap_ = on; }

 // The chains the next search may cross (one flag per chain), at `crossing_cost`; with
 // `any`, every other chain too, at `added_crossing_cost`.
 void allow_crossing(const std::vector<char>* chains, bool any) {
   crossable_ = chains;
   cross_any_ = any;
 }

 // Negotiation: the search may go through other chains' paths (not stations) at
 // evict_cost * (1 + history of the grid node).
 void set_negotiation(bool on) { negotiate_ = on; }
 void set_history(const std::vector<float>* history) { history_ = history; }

 private:
  static double distance_to_segment(double x, double y, XY a, XY b) {
    double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? std::clamp(((x - a.x) * dx + (y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
    return std::hypot(x - (a.x + t * dx), y - (a.y + t * dy));
  }

  double eviction_price(int node) const {
    return p_.evict_cost * (1.0 + (history_ ? (*history_)[static_cast<std::size_t>(node)] : 0.0));
  }

  // The cost of crossing the path of chain `other`, or infinity when that is not allowed.
  double crossing_price(int other) const {
    if (other < 0) return kInf;
    if (crossable_ && (*crossable_)[static_cast<std::size_t>(other)]) return p_.crossing_cost;
    return cross_any_ ? p_.added_crossing_cost : kInf;
  }

  GridGraph& grid_;
  const GridRouteParams& p_;
  const std::vector<char>* crossable_ = nullptr;
  bool cross_any_ = false;
  XY corridor_a_, corridor_b_;
  double corridor_slack_ = 0;
  bool overlap_ = false;
  bool negotiate_ = false;
  const std::vector<float>* history_ = nullptr;
  std::vector<double> cost_;
  std::vector<long> parent_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t now_ = 0;
  std::vector<double> target_cost_;
  struct Arrival {
    long goal, parent;
    double total;
  };
  std::vector<Arrival> goal_parents_;
};

// The ports a station's edges should use: distinct octilinear directions, in the circular
// order of the edges' geographic directions, as close to those directions as possible (the
// least total angular deviation over every order-keeping choice). Up to 8 edges.
std::vector<int> plan_ports(const std::vector<double>& angles) {
  std::size_t k = angles.size();
  std::vector<int> best(k, -1);
  if (k == 0 || k > 8) return best;
  std::vector<std::size_t> order(k);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return angles[a] < angles[b]; });
  auto deviation = [](double angle, int port) {
    double d = std::fmod(std::abs(angle - port * M_PI / 4), 2 * M_PI);
    return std::min(d, 2 * M_PI - d);
  };
  double best_cost = kInf;
  // Choose k of the 8 ports (a bit mask), then rotate which sorted edge gets the first one.
  for (int mask = 0; mask < 256; ++mask) {
    if (__builtin_popcount(mask) != static_cast<int>(k)) continue;
    std::vector<int> ports;
    for (int q = 0; q < 8; ++q)
      if (mask & (1 << q)) ports.push_back(q);
    for (std::size_t rot = 0; rot < k; ++rot) {
      double cost = 0;
      for (std::size_t i = 0; i < k; ++i) cost += deviation(angles[order[i]], ports[(i + rot) % k]);
      if (cost < best_cost) {
        best_cost = cost;
        for (std::size_t i = 0; i < k; ++i) best[order[i]] = ports[(i + rot) % k];
      }
    }
  }
  return best;
}

int direction_between(const GridGraph& g, int a, int b) {
  int dx = b % g.w - a % g.w, dy = b / g.w - a / g.w;
  for (int d = 0; d < 8; ++d)
    if (kDx[d] == dx && kDy[d] == dy) return d;
  return -1;
}

// Point at arc-length fraction t along a polyline (its ends exactly at t = 0 and 1).
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

// The part of a polyline between arc fractions t0 < t1.
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

// Drops interior points where the direction does not change.
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

struct Attempt {
  Layout layout;
  std::size_t ripups = 0;
  std::size_t overlapping = 0;      // chains routed through other paths
  std::size_t crossing_routes = 0;  // chains that cross paths they do not cross geographically
  std::size_t failed = 0;  // edges
  std::vector<int> failed_chains;
  std::size_t grid_nodes = 0;
  bool timed_out = false;
};

Attempt attempt_routing(const LayoutGraph& g, const std::vector<XY>& start, const std::vector<Chain>& chains,
                        const std::vector<bool>& anchor, const std::vector<std::vector<char>>& geo_crossing,
                        const GridRouteParams& p, double cell, const std::vector<int>& first,
                        Clock::time_point deadline) {
  Attempt result;
  std::size_t n = g.pos.size();
  // Grid over the stretched positions with room around them.
  double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  for (const auto& q : start) {
    x0 = std::min(x0, q.x);
    y0 = std::min(y0, q.y);
    x1 = std::max(x1, q.x);
    y1 = std::max(y1, q.y);
  }
  if (start.empty()) x0 = y0 = x1 = y1 = 0;
  int margin = p.candidate_radius + 8;
  GridGraph grid;
  grid.cell = cell;
  grid.origin = {x0 - margin * cell, y0 - margin * cell};
  grid.w = static_cast<int>(std::ceil((x1 - x0) / cell)) + 2 * margin + 1;
  grid.h = static_cast<int>(std::ceil((y1 - y0) / cell)) + 2 * margin + 1;
  grid.resize(static_cast<std::size_t>(grid.w) * grid.h);
  result.grid_nodes = grid.used.size();
  Router router(grid, p);

  auto in_cells = [&](XY q) { return XY{(q.x - grid.origin.x) / cell, (q.y - grid.origin.y) / cell}; };
  std::vector<int> node_at(n, -1);  // grid node of each placed anchor
  struct PortUse {
    int chain;
    double angle;  // geographic angle of the chain leaving the anchor
  };
  std::vector<std::array<int, 8>> port_chain(n);
  for (auto& a : port_chain) a.fill(-1);
  std::vector<std::vector<std::pair<int, double>>> anchor_ports(n);  // (port, geo angle)

  std::vector<std::array<int, 2>> planned(chains.size(), {-1, -1});  // port at front / back anchor
  auto geo_angle = [&](const Chain& c, bool from_front) {
    std::uint32_t a = from_front ? c.nodes[0] : c.nodes.back();
    std::uint32_t b = from_front ? c.nodes[1] : c.nodes[c.nodes.size() - 2];
    return std::atan2(g.pos[b].y - g.pos[a].y, g.pos[b].x - g.pos[a].x);
  };
  {
    std::vector<std::vector<std::pair<int, bool>>> ends(n);  // (chain, at its front)
    for (int ci = 0; ci < static_cast<int>(chains.size()); ++ci) {
      ends[chains[ci].nodes.front()].push_back({ci, true});
      ends[chains[ci].nodes.back()].push_back({ci, false});
    }
    for (std::uint32_t v = 0; v < n; ++v) {
      std::vector<double> angles;
      for (auto [ci, front] : ends[v]) angles.push_back(geo_angle(chains[ci], front));
      auto ports = plan_ports(angles);
      for (std::size_t i = 0; i < ends[v].size(); ++i) planned[ends[v][i].first][ends[v][i].second ? 0 : 1] = ports[i];
    }
  }
  // Whether leaving v through port d (geographic direction theta) keeps the ports in the
  // circular order of the geographic directions, with enough free ports in every gap for the
  // edges still to be routed there (so that no later edge is left without an in-order port).
  std::vector<std::vector<double>> end_angles(n);
  for (const auto& c : chains) {
    end_angles[c.nodes.front()].push_back(geo_angle(c, true));
    end_angles[c.nodes.back()].push_back(geo_angle(c, false));
  }
  auto keeps_order = [&](std::uint32_t v, double theta, int d) {
    std::vector<std::pair<double, int>> fixed;  // (angle, port)
    for (auto [port, angle] : anchor_ports[v]) fixed.push_back({angle, port});
    fixed.push_back({theta, d});
    std::sort(fixed.begin(), fixed.end());
    std::vector<double> pending = end_angles[v];
    for (const auto& f : fixed)
      if (auto it = std::find(pending.begin(), pending.end(), f.first); it != pending.end()) pending.erase(it);
    int turns = 0;
    for (std::size_t i = 0; i < fixed.size(); ++i) {
      const auto [a0, p0] = fixed[i];
      const auto [a1, p1] = fixed[(i + 1) % fixed.size()];
      const int gap = fixed.size() == 1 ? 8 : (p1 - p0 + 8) % 8;  // ports counter-clockwise from p0 to p1
      turns += gap;
      int due = 0;  // pending edges whose direction lies between a0 and a1
      for (double a : pending) due += fixed.size() == 1 || (a0 < a1 ? (a > a0 && a < a1) : (a > a0 || a < a1));
      if (gap == 0 || gap - 1 < due) return false;
    }
    return turns == 8;  // once round: the ports are in the angles' cyclic order
  };
  auto endpoint = [&](std::uint32_t v, const Chain& c, int chain_id, bool front, int radius) {
    Endpoint ep;
    ep.station = static_cast<int>(v);
    XY centre = in_cells(start[v]);
    ep.centre = centre;
    ep.radius = node_at[v] >= 0 ? 0 : radius;
    if (node_at[v] >= 0) {
      ep.nodes.push_back({node_at[v], 0.0});
      ep.centre = {static_cast<double>(node_at[v] % grid.w), static_cast<double>(node_at[v] / grid.w)};
    } else {
      int cx = static_cast<int>(std::lround(centre.x)), cy = static_cast<int>(std::lround(centre.y));
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          int x = cx + dx, y = cy + dy;
          if (!grid.inside(x, y) || grid.used[grid.at(x, y)] != 0) continue;
          double move = std::hypot(x - centre.x, y - centre.y);
          ep.nodes.push_back({grid.at(x, y), p.move_cost * move});
        }
    }
    // Ports: free ones, in the circular order of the anchor's geographic edge directions.
    double theta = geo_angle(c, front);
    for (int d = 0; d < 8; ++d) ep.allowed[d] = port_chain[v][d] < 0;
    std::array<bool, 8> in_order;
    for (int d = 0; d < 8; ++d) in_order[d] = ep.allowed[d] && keeps_order(v, theta, d);
    // A line that continues through the anchor would rather go straight on.
    for (int d = 0; d < 8; ++d) {
      double cost = 0;
      for (int q = 0; q < 8; ++q) {
        int other = port_chain[v][q];
        if (other < 0 || other == chain_id) continue;
        const auto& ol = chains[other].lines;
        std::size_t shared = 0;
        for (auto l : c.lines) shared += std::binary_search(ol.begin(), ol.end(), l);
        if (shared) cost += p.line_bend_weight * shared * p.bend_cost[std::min(turn(d, (q + 4) % 8), 3)];
      }
      int plan = planned[chain_id][front ? 0 : 1];
      if (plan >= 0) cost += p.port_plan_weight * turn(d, plan);
      ep.port_cost[d] = cost + (in_order[d] ? 0.0 : p.order_penalty);
    }
    // When no free port keeps the order, the penalty would only slow the search down.
    bool any_in_order = false;
    for (int d = 0; d < 8; ++d) any_in_order = any_in_order || (ep.allowed[d] && in_order[d]);
    if (!any_in_order)
      for (int d = 0; d < 8; ++d)
        if (!in_order[d]) ep.port_cost[d] -= p.order_penalty;
    return ep;
  };

  // Place every anchor first, on the free grid node nearest to its stretched position with no
  // other station next to it: routes then run between fixed ends and keep each station on its
  // geographic side of the others' paths (placing ends while routing let early paths wall in
  // stations that were placed later).
  auto place = [&](std::uint32_t v, int node) {
    node_at[v] = node;
    grid.used[node] = 2;
    int x = node % grid.w, y = node / grid.w;
    for (int d = 0; d < 8; ++d)
      if (grid.inside(x + kDx[d], y + kDy[d]) && grid.reserved_for[grid.at(x + kDx[d], y + kDy[d])] < 0)
        grid.reserved_for[grid.at(x + kDx[d], y + kDy[d])] = static_cast<int>(v);
  };
  {
    std::vector<std::uint32_t> anchors;
    for (std::uint32_t v = 0; v < n; ++v)
      if (anchor[v]) anchors.push_back(v);
    for (auto v : anchors) {
      XY c = in_cells(start[v]);
      int cx = static_cast<int>(std::lround(c.x)), cy = static_cast<int>(std::lround(c.y));
      int best = -1;
      double best_d = kInf;
      for (int r = 0; r <= 4 * p.candidate_radius && best < 0; ++r)
        for (int dy = -r; dy <= r; ++dy)
          for (int dx = -r; dx <= r; ++dx) {
            if (std::max(std::abs(dx), std::abs(dy)) != r) continue;  // ring r
            int x = cx + dx, y = cy + dy;
            if (!grid.inside(x, y) || grid.used[grid.at(x, y)] != 0) continue;
            bool crowded = false;
            for (int k = 0; k < 8; ++k)
              crowded = crowded || (grid.inside(x + kDx[k], y + kDy[k]) && grid.used[grid.at(x + kDx[k], y + kDy[k])] == 2);
            double dist = std::hypot(x - c.x, y - c.y);
            if (!crowded && dist < best_d) {
              best_d = dist;
              best = grid.at(x, y);
            }
          }
      if (best >= 0) place(v, best);
    }
  }

  // Route chains breadth-first from the busiest anchor; more lines first at each anchor.
  std::vector<std::vector<int>> chains_at(n);
  for (int i = 0; i < static_cast<int>(chains.size()); ++i) {
    chains_at[chains[i].nodes.front()].push_back(i);
    chains_at[chains[i].nodes.back()].push_back(i);
  }
  for (auto& list : chains_at)
    std::sort(list.begin(), list.end(), [&](int a, int b) { return chains[a].lines.size() > chains[b].lines.size(); });
  std::vector<int> order;
  std::vector<bool> queued(chains.size(), false), visited(n, false);
  for (int ci : first) {  // chains that failed last time go first
    queued[ci] = true;
    order.push_back(ci);
  }
  std::vector<std::uint32_t> anchors_by_degree;
  for (std::uint32_t v = 0; v < n; ++v)
    if (anchor[v] && !chains_at[v].empty()) anchors_by_degree.push_back(v);
  std::stable_sort(anchors_by_degree.begin(), anchors_by_degree.end(),
                   [&](auto a, auto b) { return chains_at[a].size() > chains_at[b].size(); });
  for (auto root : anchors_by_degree) {
    if (visited[root]) continue;
    std::queue<std::uint32_t> q;
    q.push(root);
    visited[root] = true;
    while (!q.empty()) {
      auto v = q.front();
      q.pop();
      for (int ci : chains_at[v]) {
        if (queued[ci]) continue;
        queued[ci] = true;
        order.push_back(ci);
        for (auto end : {chains[ci].nodes.front(), chains[ci].nodes.back()})
          if (!visited[end]) {
            visited[end] = true;
            q.push(end);
          }
      }
    }
  }

  // Route in order; a chain whose search was walled in rips up the paths that walled it
  // and goes again before them (each chain at most a few times, rip-ups capped overall).
  std::vector<std::vector<int>> grid_path(chains.size());
  std::vector<std::array<int, 2>> ports_of(chains.size(), {-1, -1});
  // Which chains each chain may still cross: those it crosses geographically, once each.
  std::vector<std::vector<char>> crossable = geo_crossing;
  std::vector<std::vector<int>> crossed(chains.size());  // partners of the crossings on each path
  auto note_crossing = [&](int a, int b) {
    crossable[a][b] = crossable[b][a] = 0;
    crossed[a].push_back(b);
    crossed[b].push_back(a);
  };
  auto commit = [&](int ci, const std::vector<int>& path) {
    const auto& c = chains[ci];
    int first = path.front(), last = path.back();
    for (auto [v, node] : {std::pair{c.nodes.front(), first}, std::pair{c.nodes.back(), last}})
      if (node_at[v] < 0) place(v, node);
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
      const int node = path[i];
      const int din = direction_between(grid, path[i - 1], node), dout = direction_between(grid, node, path[i + 1]);
      const auto axis = static_cast<std::int8_t>(din == dout ? din % 4 : -1);
      if (grid.used[node] == 1) {  // crossing another path
        grid.used[node] = 3;
        grid.owner2[node] = ci;
        grid.axis2[node] = axis;
        note_crossing(ci, grid.owner[node]);
      } else {
        grid.used[node] = 1;
        grid.owner[node] = ci;
        grid.axis[node] = axis;
      }
    }
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      int d = direction_between(grid, path[i], path[i + 1]);
      if (int other = grid.crossing_diagonal(path[i], d); other >= 0) note_crossing(ci, other);
      grid.take_diagonal(path[i], d, ci);
    }
    int out_port = direction_between(grid, first, path[1]);
    int in_port = direction_between(grid, last, path[path.size() - 2]);
    port_chain[c.nodes.front()][out_port] = ci;
    port_chain[c.nodes.back()][in_port] = ci;
    anchor_ports[c.nodes.front()].push_back({out_port, geo_angle(c, true)});
    anchor_ports[c.nodes.back()].push_back({in_port, geo_angle(c, false)});
    ports_of[ci] = {out_port, in_port};
    grid_path[ci] = path;
  };
  auto rip_up = [&](int ci) {
    const auto& c = chains[ci];
    const auto& path = grid_path[ci];
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
      const int node = path[i];
      if (grid.used[node] == 3) {  // the other path stays
        if (grid.owner[node] == ci) {
          grid.owner[node] = grid.owner2[node];
          grid.axis[node] = grid.axis2[node];
        }
        grid.owner2[node] = -1;
        grid.axis2[node] = -1;
        grid.used[node] = 1;
      } else {
        grid.used[node] = 0;
        grid.owner[node] = -1;
        grid.axis[node] = -1;
      }
    }
    for (int other : crossed[ci]) {
      crossable[ci][other] = crossable[other][ci] = geo_crossing[ci][other];
      auto& list = crossed[other];
      list.erase(std::find(list.begin(), list.end(), ci));
    }
    crossed[ci].clear();
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
      grid.release_diagonal(path[i], direction_between(grid, path[i], path[i + 1]));
    for (auto [v, port] : {std::pair{c.nodes.front(), ports_of[ci][0]}, std::pair{c.nodes.back(), ports_of[ci][1]}}) {
      port_chain[v][port] = -1;
      auto& list = anchor_ports[v];
      // Captured by copy: clang 14 cannot capture structured bindings by reference.
      list.erase(std::remove_if(list.begin(), list.end(), [port = port](auto e) { return e.first == port; }), list.end());
    }
    grid_path[ci].clear();
  };
  bool crossing_any = false;
  auto try_route = [&](int ci) {
    const auto& c = chains[ci];
    std::vector<int> path;
    for (int radius : {p.candidate_radius, 2 * p.candidate_radius + 2}) {
      auto src = endpoint(c.nodes.front(), c, ci, true, radius);
      auto dst = endpoint(c.nodes.back(), c, ci, false, radius);
      // Unplaced ends must not compete for the same node.
      if (node_at[c.nodes.front()] < 0 && node_at[c.nodes.back()] < 0) {
        std::vector<std::pair<int, double>> keep;
        for (const auto& t : dst.nodes)
          if (std::none_of(src.nodes.begin(), src.nodes.end(), [&](auto s) { return s.first == t.first; }))
            keep.push_back(t);
        dst.nodes = std::move(keep);
      }
      if (src.nodes.empty() || dst.nodes.empty()) continue;
      router.allow_crossing(&crossable[ci], crossing_any);
      path = router.route(src, dst);
      if (!path.empty() || node_at[c.nodes.front()] >= 0) break;  // a wider radius only helps unplaced ends
    }
    return path;
  };
  std::deque<int> work(order.begin(), order.end());
  std::size_t evictions = 0, max_evictions = p.evictions_per_chain * chains.size() + 16;
  std::vector<float> history(grid.used.size(), 0.0f);
  router.set_history(&history);
  // The chains a negotiated path goes through rather than legally across, with the node.
  auto conflicts = [&](int ci, const std::vector<int>& path) {
    std::vector<std::pair<int, int>> victims;
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
      const int node = path[i];
      const int din = direction_between(grid, path[i - 1], node), dout = direction_between(grid, node, path[i + 1]);
      if (grid.used[node] == 1) {
        const int other = grid.owner[node];
        const bool legal = din == dout && grid.axis[node] >= 0 && grid.axis[node] != din % 4 &&
                           (crossable[ci][other] || crossing_any);
        if (!legal) victims.push_back({other, node});
      } else if (grid.used[node] == 3) {
        victims.push_back({grid.owner[node], node});
        victims.push_back({grid.owner2[node], node});
      }
    }
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      const int other = grid.crossing_diagonal(path[i], direction_between(grid, path[i], path[i + 1]));
      if (other >= 0 && !crossable[ci][other] && !crossing_any) victims.push_back({other, path[i]});
    }
    return victims;
  };
  while (!work.empty()) {
    int ci = work.front();
    work.pop_front();
    if (!grid_path[ci].empty()) continue;
    util::check_stop();  // the request's own deadline or client, beyond the layout's time limit
    if (Clock::now() > deadline) {
      result.timed_out = true;
      break;
    }
    auto path = try_route(ci);
    if (!path.empty()) {
      commit(ci, path);
      continue;
    }
    // Walled in: negotiate (PathFinder-style). The search may go through other chains' paths
    // at a price that grows with how often that grid node was fought over; the paths it goes
    // through are torn up and queued again. History spreads the paths out until none is left
    // walled in, or the eviction budget is spent.
    if (evictions >= max_evictions) continue;
    router.set_negotiation(true);
    path = try_route(ci);
    router.set_negotiation(false);
    if (path.empty()) continue;  // not even through others: the fallbacks below try
    auto victims = conflicts(ci, path);
    for (auto [victim, node] : victims) history[static_cast<std::size_t>(node)] += p.history_step;
    for (auto [victim, node] : victims) {
      if (grid_path[victim].empty()) continue;  // already torn up (it met the path twice)
      rip_up(victim);
      work.push_back(victim);
      ++evictions;
    }
    commit(ci, path);
  }
  result.ripups = evictions;
  // Whatever is still walled in crosses paths it does not cross geographically...
  crossing_any = true;
  for (std::size_t ci = 0; ci < chains.size(); ++ci) {
    if (!grid_path[ci].empty() || Clock::now() > deadline) continue;
    auto path = try_route(static_cast<int>(ci));
    if (path.empty()) continue;
    commit(static_cast<int>(ci), path);
    ++result.crossing_routes;
  }
  crossing_any = false;
  // ...or, as the last resort, goes through other paths rather than straight across.
  router.allow_overlap(true);
  for (std::size_t ci = 0; ci < chains.size(); ++ci) {
    if (!grid_path[ci].empty()) continue;
    auto path = try_route(static_cast<int>(ci));
    if (path.empty()) continue;
    ++result.overlapping;
    const auto& c = chains[ci];
    int out_port = direction_between(grid, path.front(), path[1]);
    int in_port = direction_between(grid, path.back(), path[path.size() - 2]);
    port_chain[c.nodes.front()][out_port] = static_cast<int>(ci);
    port_chain[c.nodes.back()][in_port] = static_cast<int>(ci);
    grid_path[ci] = path;  // not committed to the grid: later overlap routes may cross it too
  }
  router.allow_overlap(false);
  std::vector<std::vector<XY>> chain_path(chains.size());
  for (std::size_t ci = 0; ci < chains.size(); ++ci) {
    if (grid_path[ci].empty()) continue;
    std::vector<XY> pts;
    for (int node : grid_path[ci]) pts.push_back(grid.point(node));
    chain_path[ci] = simplify_collinear(pts);
  }

  // Positions: anchors from the grid (or their stretched position when never routed),
  // interior stations along their chain at their share of the target length.
  auto& L = result.layout;
  L.pos.assign(n, {0, 0});
  for (std::uint32_t v = 0; v < n; ++v) L.pos[v] = node_at[v] >= 0 ? grid.point(node_at[v]) : start[v];
  L.paths.assign(g.edges.size(), {});
  for (std::size_t ci = 0; ci < chains.size(); ++ci) {
    const auto& c = chains[ci];
    if (chain_path[ci].empty()) {
      result.failed_chains.push_back(static_cast<int>(ci));
      result.failed += c.edges.size();
      for (std::size_t k = 1; k + 1 < c.nodes.size(); ++k) L.pos[c.nodes[k]] = start[c.nodes[k]];
      continue;
    }
    double total = 0;
    for (auto e : c.edges) total += g.min_length[e];
    double run = 0;
    std::vector<double> t{0.0};
    for (auto e : c.edges) {
      run += g.min_length[e];
      t.push_back(total > 0 ? run / total : double(t.size()) / c.edges.size());
    }
    for (std::size_t k = 1; k + 1 < c.nodes.size(); ++k) L.pos[c.nodes[k]] = point_along(chain_path[ci], t[k]);
    for (std::size_t k = 0; k < c.edges.size(); ++k) {
      auto piece = simplify_collinear(sub_polyline(chain_path[ci], t[k], t[k + 1]));
      if (!c.forward[k]) std::reverse(piece.begin(), piece.end());
      L.paths[c.edges[k]] = std::move(piece);
    }
  }
  for (std::size_t e = 0; e < g.edges.size(); ++e)
    if (L.paths[e].empty()) L.paths[e] = {L.pos[g.edges[e].first], L.pos[g.edges[e].second]};
  return result;
}

}  // namespace

Layout route_octilinear(const LayoutGraph& g, const std::vector<XY>& start, const GridRouteParams& p,
                        GridRouteReport* report) {
  auto begin = Clock::now();
  auto deadline = begin + std::chrono::microseconds(static_cast<long long>(p.time_limit_ms * 1000));
  // Edges that cross geographically (straight between the real positions) may cross in the
  // layout too, once per pair: a network drawn with crossings (lines that pass over each other
  // without a shared station) usually has no planar octilinear layout. Such an edge is a chain
  // of its own, so that the crossing in the layout is between the same two edges.
  std::vector<std::vector<XY>> straight;
  for (const auto& [a, b] : g.edges) straight.push_back({g.pos[a], g.pos[b]});
  auto geo_pairs = crossing_path_pairs(straight, g.edges);
  std::vector<bool> anchor(g.pos.size(), false);
  for (auto [e, f] : geo_pairs)
    for (auto edge : {e, f}) anchor[g.edges[edge].first] = anchor[g.edges[edge].second] = true;
  auto chains = contract(g, anchor);
  std::vector<int> chain_of(g.edges.size(), -1);
  for (std::size_t ci = 0; ci < chains.size(); ++ci)
    for (auto e : chains[ci].edges) chain_of[e] = static_cast<int>(ci);
  std::vector<std::vector<char>> geo_crossing(chains.size(), std::vector<char>(chains.size(), 0));
  for (auto [e, f] : geo_pairs) {
    int a = chain_of[e], b = chain_of[f];
    if (a >= 0 && b >= 0 && a != b) geo_crossing[a][b] = geo_crossing[b][a] = 1;
  }
  // Attempts are ranked by unrouted or overlapping chains, then by added crossings (pairs
  // that do not cross geographically), then by all crossings.
  auto rank = [&](const Attempt& a) {
    auto pairs = crossing_path_pairs(a.layout.paths, g.edges);
    std::vector<std::pair<std::size_t, std::size_t>> added;
    std::set_difference(pairs.begin(), pairs.end(), geo_pairs.begin(), geo_pairs.end(), std::back_inserter(added));
    return std::tuple{a.failed + a.overlapping, added.size(), pairs.size()};
  };
  Attempt best;
  std::tuple<std::size_t, std::size_t, std::size_t> best_rank;
  bool have = false;
  int used_attempt = 1;
  std::vector<int> first;
  int attempts = std::max(1, p.attempts);
  for (int a = 1; a <= attempts; ++a) {
    // Each attempt gets its share of the time, so a hard first one leaves room for the next.
    // The first two route freely (fewest bends), the second on a grid twice as fine (room in
    // dense centres); the third keeps paths in their corridors (so that detours do not wall
    // stations in).
    auto share = begin + (deadline - begin) * a / attempts;
    GridRouteParams variant = p;
    if (a <= 2) variant.corridor_cost = 0;
    const double cell = a == 2 ? p.cell / 2 : p.cell;
    auto attempt = attempt_routing(g, start, chains, anchor, geo_crossing, variant, cell, first, share);
    first = attempt.failed_chains;
    auto attempt_rank = rank(attempt);
    if (!have || attempt_rank < best_rank) {
      best = std::move(attempt);
      best_rank = attempt_rank;
      have = true;
      used_attempt = a;
    }
    if ((std::get<0>(best_rank) == 0 && std::get<1>(best_rank) == 0) || Clock::now() > deadline) break;
  }
  best.layout.method = "grid";
  best.layout.status = best.failed ? (best.timed_out ? "time_limit" : "incomplete")
                                   : best.overlapping ? "overlapping" : "ok";
  if (report) {
    report->chains = chains.size();
    report->contracted_nodes = std::count(anchor.begin(), anchor.end(), false);
    report->failed = best.failed;
    report->grid_nodes = best.grid_nodes;
    report->attempt = used_attempt;
    report->timed_out = best.timed_out;
    report->ripups = best.ripups;
    report->overlapping = best.overlapping;
    report->crossing_routes = best.crossing_routes;
    report->crossings = std::get<2>(best_rank);
    report->geo_crossings = geo_pairs.size();
  }
  return best.layout;
}

}  // namespace tourmap::metro
