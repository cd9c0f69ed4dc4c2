#include "metro/grid_router.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <stdexcept>

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
  const std::size_t states = static_cast<std::size_t>(grid.w) * grid.h * 9;
  // Parents are kept as 32-bit states (16-byte records); a grid this large would need over
  // 30 GB of state records anyway.
  if (states >= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw std::length_error("octilinear grid too large");
  states_ = static_cast<long>(states);
  state_.reset(static_cast<StateRecord*>(std::calloc(states, sizeof(StateRecord))));
  if (!state_) throw std::bad_alloc();
  target_cost_.assign(static_cast<std::size_t>(grid.w) * grid.h, kInf);
  reached_src_.assign(target_cost_.size(), 0);
  reached_dst_.assign(target_cost_.size(), 0);
}

std::vector<int> GridRouter::route(const Endpoint& src, const Endpoint& dst) {
  ++now_;
  set_corridor(src, dst);
  for (const auto& [node, c] : dst.nodes) target_cost_[node] = c;
  expansions_ = 0;
  if (!may_reach(src, dst)) {  // walled in: the search would only spend its cap of expansions
    for (const auto& [node, c] : dst.nodes) target_cost_[node] = kInf;
    return {};
  }
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

// A node a path of this search may stand on, by what occupies it (over-approximated: a path
// node that may be crossed only straight on is taken as passable in every direction).
bool GridRouter::standable(int node) const {
  const auto used = grid_.used[node];
  if (used == kFree) return true;
  if (used == kStation) return false;
  if (negotiate_ || overlap_) return true;
  return used == kPath && grid_.axis[node] >= 0 && crossing_price(grid_.owner[node]) < kInf;
}

// The diagonal step from `node` in direction d crosses a diagonal it may not cross.
bool GridRouter::diagonal_blocked(int node, int d) const {
  if (negotiate_ || overlap_) return false;
  const int other = grid_.crossing_diagonal(node, d);
  return other >= 0 && crossing_price(other) == kInf;
}

// Whether the search can reach the target at all: breadth-first from both ends at once over
// the nodes a path may stand on, the smaller frontier first, until the two meet (maybe: the
// search runs) or one side runs out of nodes (no: that end is walled in). The moves allowed
// here are a superset of the search's (no turn, port or straight-on rule), so "no" is exact,
// and costs at most twice the walled-in side's area, where the search would spend its whole
// cap of expansions (up to 240,000 states) before it gave up.
bool GridRouter::may_reach(const Endpoint& src, const Endpoint& dst) {
  frontier_src_.clear();
  frontier_dst_.clear();
  for (const auto& [node, c] : src.nodes) {
    if (target_cost_[node] < kInf) return true;
    reached_src_[node] = now_;
    frontier_src_.push_back(node);
  }
  for (const auto& [node, c] : dst.nodes) {
    reached_dst_[node] = now_;
    frontier_dst_.push_back(node);
  }
  std::size_t head_src = 0, head_dst = 0;
  while (head_src < frontier_src_.size() && head_dst < frontier_dst_.size()) {
    const bool forward = frontier_src_.size() - head_src <= frontier_dst_.size() - head_dst;
    auto& frontier = forward ? frontier_src_ : frontier_dst_;
    auto& mine = forward ? reached_src_ : reached_dst_;
    const auto& theirs = forward ? reached_dst_ : reached_src_;
    const int node = frontier[forward ? head_src++ : head_dst++];
    const int x = node % grid_.w, y = node / grid_.w;
    for (int d = 0; d < 8; ++d) {
      const int nx = x + kDx[d], ny = y + kDy[d];
      if (!grid_.inside(nx, ny)) continue;
      const int next = grid_.at(nx, ny);
      if (mine[next] == now_ || diagonal_blocked(node, d)) continue;
      if (theirs[next] == now_) return true;
      if (!standable(next)) continue;
      mine[next] = now_;
      frontier.push_back(next);
    }
  }
  return false;
}

// Octile distance to the target's candidate area: admissible, as a step costs at least its length.
double GridRouter::heuristic(int node, const Endpoint& dst) const {
  return heuristic_at(node % grid_.w, node / grid_.w, dst);
}

double GridRouter::heuristic_at(int x, int y, const Endpoint& dst) const {
  double dx = std::abs(x - dst.centre.x), dy = std::abs(y - dst.centre.y);
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
  auto& r = state_[static_cast<std::size_t>(s)];
  if (r.stamp != now_ || c < r.cost) {
    r = {c, static_cast<std::int32_t>(parent), now_};
    return true;
  }
  return false;
}

// Runs the search from the states in `open`; the goal state reached, or -1. A goal is queued as
// state goal_base + (node * 9 + arrival direction), with its total cost, when a step reaches a
// target node; the first goal popped is the cheapest.
long GridRouter::search(OpenList& open, const Endpoint& src, const Endpoint& dst) {
  const long goal_base = states_;
  double best_goal = kInf;
  std::size_t expansions = 0;
  // Long routes may explore more; hopeless ones still stop.
  double reach = heuristic(src.nodes.front().first, dst) + 10;
  std::size_t cap = std::min<std::size_t>(p_.max_expansions * 8,
                                          std::max<std::size_t>(p_.max_expansions, 60 * reach * reach));
  // A path dearer than max_detour times the straight way is a detour a reader would not follow
  // (Berlin had paths of 240 cells between ends 42 apart, each costing 100,000 expansions): give
  // up, and let negotiation tear up what walls the straight way in. (Not in negotiation and the
  // fallbacks: their prices for going through others are meant to be paid.)
  const bool plain = !negotiate_ && !overlap_ && !cross_any_;
  const double f_limit = plain ? p_.max_detour * reach + p_.detour_slack : kInf;
  while (!open.empty()) {
    expansions_ = expansions;
    if (++expansions > cap) break;
    auto [f, s] = open.top();
    open.pop();
    if (s >= goal_base) return s - goal_base;
    if (f > f_limit) break;
    if (f > best_goal) break;
    const int node = static_cast<int>(s / 9);
    const auto& r = state_[static_cast<std::size_t>(s)];
    if (r.stamp != now_ || f - heuristic(node, dst) > r.cost + 1e-9) continue;  // stale
    expand(open, s, src, dst, best_goal);
  }
  return -1;
}

void GridRouter::expand(OpenList& open, long s, const Endpoint& src, const Endpoint& dst, double& best_goal) {
  const int node = static_cast<int>(s / 9), din = static_cast<int>(s % 9);
  const double c = state_[static_cast<std::size_t>(s)].cost;
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
    // Straight steps never cross a diagonal, and most nodes are free: no call for those.
    const auto diagonal = (d & 1) ? diagonal_price(node, d) : std::optional<double>(0.0);
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
        open.push({total, states_ + gs});
        goal_parents_.push_back({gs, s, total});
      }
    }
    const auto occupancy = grid_.used[next] == kFree ? std::optional<double>(0.0) : occupancy_price(next, d);
    if (!occupancy) continue;
    step += *occupancy;
    step += reserved_price(next, src, dst);
    step += corridor_price(nx, ny);
    long ns = static_cast<long>(next) * 9 + d;
    if (relax(ns, step, s)) open.push({step + heuristic_at(nx, ny, dst), ns});
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
  for (long s = parent; s >= 0; s = state_[static_cast<std::size_t>(s)].parent) path.push_back(static_cast<int>(s / 9));
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
