#include "metro/grid_router.hpp"

#include <algorithm>
#include <cmath>

namespace tourmap::metro::octi {

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

GridRouter::GridRouter(GridGraph& grid, const GridRouteParams& p) : grid_(grid), p_(p) {
  std::size_t states = static_cast<std::size_t>(grid.w) * grid.h * 9;
  cost_.assign(states, kInf);
  parent_.assign(states, -1);
  stamp_.assign(states, 0);
  target_cost_.assign(static_cast<std::size_t>(grid.w) * grid.h, kInf);
}

std::vector<int> GridRouter::route(const Endpoint& src, const Endpoint& dst) {
  ++now_;
  set_corridor(src, dst);
  for (const auto& [node, c] : dst.nodes) target_cost_[node] = c;
  OpenList open;
  for (const auto& [node, c] : src.nodes) {
    long s = static_cast<long>(node) * 9 + kNoDir;
    if (relax(s, c, -1)) open.push({c + heuristic(node, dst), s});
  }
  const long found = search(open, src, dst);
  for (const auto& [node, c] : dst.nodes) target_cost_[node] = kInf;
  if (found < 0) {
    goal_parents_.clear();
    return {};
  }
  return without_loops(trace_back(found));
}

// Octile distance to the target's candidate area: admissible, as a step costs at least its length.
double GridRouter::heuristic(int node, const Endpoint& dst) const {
  double dx = std::abs(node % grid_.w - dst.centre.x), dy = std::abs(node / grid_.w - dst.centre.y);
  double oct = std::max(dx, dy) + (std::sqrt(2.0) - 1) * std::min(dx, dy);
  return std::max(0.0, oct - dst.radius * std::sqrt(2.0));
}

// The straight line from the first source candidate to the target's centre, in cells.
void GridRouter::set_corridor(const Endpoint& src, const Endpoint& dst) {
  corridor_a_ = {static_cast<double>(src.nodes.front().first % grid_.w), static_cast<double>(src.nodes.front().first / grid_.w)};
  corridor_b_ = dst.centre;
  corridor_slack_ = std::max(p_.corridor_slack,
                             p_.corridor_share * std::hypot(corridor_b_.x - corridor_a_.x, corridor_b_.y - corridor_a_.y));
}

// Records cost c for state s when it is new in this search or cheaper.
bool GridRouter::relax(long s, double c, long parent) {
  if (stamp_[s] != now_ || c < cost_[s]) {
    stamp_[s] = now_;
    cost_[s] = c;
    parent_[s] = parent;
    return true;
  }
  return false;
}

// Runs the search from the states in `open`; the goal state reached, or -1. A goal is queued as
// state goal_base + (node * 9 + arrival direction), with its total cost, when a step reaches a
// target node; the first goal popped is the cheapest.
long GridRouter::search(OpenList& open, const Endpoint& src, const Endpoint& dst) {
  const long goal_base = static_cast<long>(cost_.size());
  double best_goal = kInf;
  std::size_t expansions = 0;
  // Long routes may explore more; hopeless ones still stop.
  double reach = heuristic(src.nodes.front().first, dst) + 10;
  std::size_t cap = std::min<std::size_t>(p_.max_expansions * 8,
                                          std::max<std::size_t>(p_.max_expansions, 60 * reach * reach));
  while (!open.empty()) {
    if (++expansions > cap) break;
    auto [f, s] = open.top();
    open.pop();
    if (s >= goal_base) return s - goal_base;
    if (f > best_goal) break;
    const int node = static_cast<int>(s / 9);
    if (stamp_[s] != now_ || f - heuristic(node, dst) > cost_[s] + 1e-9) continue;  // stale
    expand(open, s, src, dst, best_goal);
  }
  return -1;
}

void GridRouter::expand(OpenList& open, long s, const Endpoint& src, const Endpoint& dst, double& best_goal) {
  const int node = static_cast<int>(s / 9), din = static_cast<int>(s % 9);
  const double c = cost_[s];
  const int x = node % grid_.w, y = node / grid_.w;
  const bool straight_only = straight_on_only(node, din);
  for (int d = 0; d < 8; ++d) {
    if (straight_only && d != din) continue;
    const auto turn_cost = turn_price(src, din, d);
    if (!turn_cost) continue;
    double step = c + *turn_cost;
    int nx = x + kDx[d], ny = y + kDy[d];
    if (!grid_.inside(nx, ny)) continue;
    int next = grid_.at(nx, ny);
    const auto diagonal = diagonal_price(node, d);
    if (!diagonal) continue;
    step += *diagonal;
    step += (d % 2) ? std::sqrt(2.0) : 1.0;
    // Arriving at a target node: queue the goal with the cost of ending there.
    if (double tc = target_cost_[next]; tc < kInf) {
      int port = (d + 4) % 8;
      if (dst.allowed[port]) {
        double total = step + tc + dst.port_cost[port];
        long gs = static_cast<long>(next) * 9 + d;
        best_goal = std::min(best_goal, total);
        open.push({total, static_cast<long>(cost_.size()) + gs});
        goal_parents_.push_back({gs, s, total});
      }
    }
    const auto occupancy = occupancy_price(next, d);
    if (!occupancy) continue;
    step += *occupancy;
    step += reserved_price(next, src, dst);
    step += corridor_price(nx, ny);
    long ns = static_cast<long>(next) * 9 + d;
    if (relax(ns, step, s)) open.push({step + heuristic(next, dst), ns});
  }
}

// Crossing another path here: straight on only. (Negotiating, the search may also have come
// through to tear that path up: then it may turn.)
bool GridRouter::straight_on_only(int node, int din) const {
  return !overlap_ && din != kNoDir && grid_.used[node] != kFree &&
         (!negotiate_ || (grid_.used[node] == kPath && grid_.axis[node] >= 0 && grid_.axis[node] != din % 4 &&
                          crossing_price(grid_.owner[node]) < kInf));
}

// Leaving the source through port d (when allowed), or turning from din to d (never back).
std::optional<double> GridRouter::turn_price(const Endpoint& src, int din, int d) const {
  if (din == kNoDir) {
    if (!src.allowed[d]) return std::nullopt;
    return src.port_cost[d];
  }
  int t = turn(din, d);
  if (t == 4) return std::nullopt;
  return p_.bend_cost[t];
}

// A diagonal step across another path's diagonal in the same cell; nullopt when not allowed.
std::optional<double> GridRouter::diagonal_price(int node, int d) const {
  int other = grid_.crossing_diagonal(node, d);
  if (other < 0) return 0.0;
  double price = crossing_price(other);
  if (price == kInf) {
    if (negotiate_) return eviction_price(node);
    if (overlap_) return p_.overlap_cost;
    return std::nullopt;
  }
  return price;
}

// Stepping onto `next` in direction d: free, across a path, through it (negotiating or
// overlapping); nullopt when not allowed (stations always).
std::optional<double> GridRouter::occupancy_price(int next, int d) const {
  if (grid_.used[next] == kFree) return 0.0;
  // A path going straight through `next` on another axis may be crossed there.
  double price = grid_.used[next] == kPath && grid_.axis[next] >= 0 && grid_.axis[next] != d % 4
                     ? crossing_price(grid_.owner[next])
                     : kInf;
  if (price == kInf) {
    if (grid_.used[next] == kStation) return std::nullopt;
    if (negotiate_) return eviction_price(next) * (grid_.used[next] == kCrossing ? 2 : 1);
    if (overlap_) return p_.overlap_cost;
    return std::nullopt;
  }
  return price;
}

// Passing right next to a station other than the path's own ends.
double GridRouter::reserved_price(int next, const Endpoint& src, const Endpoint& dst) const {
  int owner = grid_.reserved_for[next];
  return owner >= 0 && owner != src.station && owner != dst.station ? p_.reserved_penalty : 0.0;
}

// Stay near the straight corridor between the ends: long detours wall in other stations.
double GridRouter::corridor_price(int nx, int ny) const {
  if (p_.corridor_cost > 0) {
    double off = distance_to_segment(nx, ny, corridor_a_, corridor_b_);
    if (off > corridor_slack_) return p_.corridor_cost * (off - corridor_slack_);
  }
  return 0.0;
}

// The grid nodes from the source to the goal state `found`. The goal state's parent is its
// cheapest recorded arrival.
std::vector<int> GridRouter::trace_back(long found) {
  long parent = -1;
  double best = kInf;
  for (const auto& arrival : goal_parents_)
    if (arrival.goal == found && arrival.total < best) {
      best = arrival.total;
      parent = arrival.parent;
    }
  goal_parents_.clear();
  std::vector<int> path{static_cast<int>(found / 9)};
  for (long s = parent; s >= 0; s = parent_[s]) path.push_back(static_cast<int>(s / 9));
  std::reverse(path.begin(), path.end());
  return path;
}

double GridRouter::distance_to_segment(double x, double y, XY a, XY b) {
  double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? std::clamp(((x - a.x) * dx + (y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(x - (a.x + t * dx), y - (a.y + t * dy));
}

double GridRouter::eviction_price(int node) const {
  return p_.evict_cost * (1.0 + (history_ ? (*history_)[static_cast<std::size_t>(node)] : 0.0));
}

// The cost of crossing the path of chain `other`, or infinity when that is not allowed.
double GridRouter::crossing_price(int other) const {
  if (other < 0) return kInf;
  if (crossable_ && (*crossable_)[static_cast<std::size_t>(other)]) return p_.crossing_cost;
  return cross_any_ ? p_.added_crossing_cost : kInf;
}

}  // namespace tourmap::metro::octi
