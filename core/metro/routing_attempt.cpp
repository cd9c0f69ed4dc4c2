#include "metro/routing_attempt.hpp"

#include "metro/port_planning.hpp"
#include "util/stop.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <queue>
#include <tuple>

namespace tourmap::metro::octi {

RoutingAttempt::RoutingAttempt(const LayoutGraph& g, const std::vector<XY>& start, const std::vector<Chain>& chains,
                               const std::vector<bool>& anchor, const std::vector<std::vector<char>>& geo_crossing,
                               const GridRouteParams& p, double cell)
    : g_(g),
      start_(start),
      chains_(chains),
      anchor_(anchor),
      geo_crossing_(geo_crossing),
      p_(p),
      n_(g.pos.size()),
      // Grid over the stretched positions with room around them.
      grid_(grid_around(start, cell, p.candidate_radius + 8)),
      router_(grid_, p),
      node_at_(n_, -1),
      port_chain_(n_),
      anchor_ports_(n_),
      planned_(plan_chain_ports(g, chains)),
      end_angles_(chain_end_angles(g, chains)),
      grid_path_(chains.size()),
      ports_of_(chains.size(), {-1, -1}),
      crossable_(geo_crossing),
      crossed_(chains.size()),
      out_of_order_(chains.size(), false) {
  result_.grid_nodes = grid_.used.size();
  for (auto& a : port_chain_) a.fill(-1);
}

AttemptResult RoutingAttempt::run(const std::vector<int>& first, Clock::time_point deadline) {
  place_anchors();
  route_negotiating(routing_order(first), deadline);
  route_crossing_any(deadline);
  route_overlapping();
  build_layout();
  return std::move(result_);
}

// ---- placing the anchors --------------------------------------------------------------------

XY RoutingAttempt::in_cells(XY q) const {
  return XY{(q.x - grid_.origin.x) / grid_.cell, (q.y - grid_.origin.y) / grid_.cell};
}

// Puts station v on grid node `node`; the free nodes around it are kept for its ports.
void RoutingAttempt::place(std::uint32_t v, int node) {
  node_at_[v] = node;
  grid_.used[node] = kStation;
  int x = node % grid_.w, y = node / grid_.w;
  for (int d = 0; d < 8; ++d)
    if (grid_.inside(x + kDx[d], y + kDy[d]) && grid_.reserved_for[grid_.at(x + kDx[d], y + kDy[d])] < 0)
      grid_.reserved_for[grid_.at(x + kDx[d], y + kDy[d])] = static_cast<int>(v);
}

// The free grid node nearest to `c` (in cells) with no station next to it, searched in rings
// out to 4 candidate radii; -1 when there is none.
int RoutingAttempt::anchor_node_near(XY c) const {
  int cx = static_cast<int>(std::lround(c.x)), cy = static_cast<int>(std::lround(c.y));
  int best = -1;
  double best_d = kInf;
  for (int r = 0; r <= 4 * p_.candidate_radius && best < 0; ++r)
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        if (std::max(std::abs(dx), std::abs(dy)) != r) continue;  // ring r
        int x = cx + dx, y = cy + dy;
        if (!grid_.inside(x, y) || grid_.used[grid_.at(x, y)] != kFree) continue;
        bool crowded = false;
        for (int k = 0; k < 8; ++k)
          crowded = crowded || (grid_.inside(x + kDx[k], y + kDy[k]) && grid_.used[grid_.at(x + kDx[k], y + kDy[k])] == kStation);
        double dist = std::hypot(x - c.x, y - c.y);
        if (!crowded && dist < best_d) {
          best_d = dist;
          best = grid_.at(x, y);
        }
      }
  return best;
}

// Place every anchor first, on the free grid node nearest to its stretched position with no
// other station next to it: routes then run between fixed ends and keep each station on its
// geographic side of the others' paths (placing ends while routing let early paths wall in
// stations that were placed later).
void RoutingAttempt::place_anchors() {
  for (std::uint32_t v = 0; v < n_; ++v) {
    if (!anchor_[v]) continue;
    int best = anchor_node_near(in_cells(start_[v]));
    if (best >= 0) place(v, best);
  }
}

// ---- the order of the chains ----------------------------------------------------------------

// Per station: the chains that end there, more lines first.
std::vector<std::vector<int>> RoutingAttempt::chains_at_anchors() const {
  std::vector<std::vector<int>> chains_at(n_);
  for (int i = 0; i < static_cast<int>(chains_.size()); ++i) {
    chains_at[chains_[i].nodes.front()].push_back(i);
    chains_at[chains_[i].nodes.back()].push_back(i);
  }
  for (auto& list : chains_at)
    std::sort(list.begin(), list.end(), [&](int a, int b) { return chains_[a].lines.size() > chains_[b].lines.size(); });
  return chains_at;
}

// Route chains breadth-first from the busiest anchor; more lines first at each anchor.
std::vector<int> RoutingAttempt::routing_order(const std::vector<int>& first) const {
  const auto chains_at = chains_at_anchors();
  std::vector<int> order;
  std::vector<bool> queued(chains_.size(), false), visited(n_, false);
  for (int ci : first) {  // chains that failed last time go first
    queued[ci] = true;
    order.push_back(ci);
  }
  std::vector<std::uint32_t> anchors_by_degree;
  for (std::uint32_t v = 0; v < n_; ++v)
    if (anchor_[v] && !chains_at[v].empty()) anchors_by_degree.push_back(v);
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
        for (auto end : {chains_[ci].nodes.front(), chains_[ci].nodes.back()})
          if (!visited[end]) {
            visited[end] = true;
            q.push(end);
          }
      }
    }
  }
  return order;
}

// ---- the ends of a search -------------------------------------------------------------------

// Chain `chain_id` at station v (its front or back anchor): the station's grid node once it is
// placed, else the free nodes within `radius` cells of its stretched position.
Endpoint RoutingAttempt::endpoint(std::uint32_t v, int chain_id, bool front, int radius) const {
  Endpoint ep;
  ep.station = static_cast<int>(v);
  ep.centre = in_cells(start_[v]);
  ep.radius = node_at_[v] >= 0 ? 0 : radius;
  add_candidate_nodes(ep, v, radius);
  set_port_costs(ep, v, chain_id, front);
  return ep;
}

void RoutingAttempt::add_candidate_nodes(Endpoint& ep, std::uint32_t v, int radius) const {
  if (node_at_[v] >= 0) {
    ep.nodes.push_back({node_at_[v], 0.0});
    ep.centre = {static_cast<double>(node_at_[v] % grid_.w), static_cast<double>(node_at_[v] / grid_.w)};
    return;
  }
  const XY centre = ep.centre;
  int cx = static_cast<int>(std::lround(centre.x)), cy = static_cast<int>(std::lround(centre.y));
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      int x = cx + dx, y = cy + dy;
      if (!grid_.inside(x, y) || grid_.used[grid_.at(x, y)] != kFree) continue;
      double move = std::hypot(x - centre.x, y - centre.y);
      ep.nodes.push_back({grid_.at(x, y), p_.move_cost * move});
    }
}

// Ports: free ones, in the circular order of the anchor's geographic edge directions.
void RoutingAttempt::set_port_costs(Endpoint& ep, std::uint32_t v, int chain_id, bool front) const {
  double theta = end_angle(g_, chains_[chain_id], front);
  for (int d = 0; d < 8; ++d) ep.allowed[d] = port_chain_[v][d] < 0;
  std::array<bool, 8> in_order;
  for (int d = 0; d < 8; ++d) in_order[d] = ep.allowed[d] && keeps_circular_order(anchor_ports_[v], end_angles_[v], theta, d);
  for (int d = 0; d < 8; ++d) {
    double cost = line_bend_cost(v, chain_id, d);
    int plan = planned_[chain_id][front ? 0 : 1];
    if (plan >= 0) cost += p_.port_plan_weight * turn(d, plan);
    ep.port_cost[d] = cost + (in_order[d] ? 0.0 : p_.order_penalty);
  }
  // When no free port keeps the order, the penalty would only slow the search down.
  bool any_in_order = false;
  for (int d = 0; d < 8; ++d) any_in_order = any_in_order || (ep.allowed[d] && in_order[d]);
  if (!any_in_order)
    for (int d = 0; d < 8; ++d)
      if (!in_order[d]) ep.port_cost[d] -= p_.order_penalty;
}

// A line that continues through the anchor would rather go straight on: the bend cost, per
// shared line, between port d and each port already taken by another chain at v.
double RoutingAttempt::line_bend_cost(std::uint32_t v, int chain_id, int d) const {
  const auto& lines = chains_[chain_id].lines;
  double cost = 0;
  for (int q = 0; q < 8; ++q) {
    int other = port_chain_[v][q];
    if (other < 0 || other == chain_id) continue;
    const auto& ol = chains_[other].lines;
    std::size_t shared = 0;
    for (auto l : lines) shared += std::binary_search(ol.begin(), ol.end(), l);
    if (shared) cost += p_.line_bend_weight * shared * p_.bend_cost[std::min(turn(d, (q + 4) % 8), 3)];
  }
  return cost;
}

// ---- paths on the grid ----------------------------------------------------------------------

// A path for chain ci in the router's current mode; empty when there is none. Unplaced ends
// get a second chance with a wider radius.
std::vector<int> RoutingAttempt::try_route(int ci) {
  const auto& c = chains_[ci];
  std::vector<int> path;
  for (int radius : {p_.candidate_radius, 2 * p_.candidate_radius + 2}) {
    auto src = endpoint(c.nodes.front(), ci, true, radius);
    auto dst = endpoint(c.nodes.back(), ci, false, radius);
    // Unplaced ends must not compete for the same node.
    if (node_at_[c.nodes.front()] < 0 && node_at_[c.nodes.back()] < 0) {
      std::vector<std::pair<int, double>> keep;
      for (const auto& t : dst.nodes)
        if (std::none_of(src.nodes.begin(), src.nodes.end(), [&](auto s) { return s.first == t.first; }))
          keep.push_back(t);
      dst.nodes = std::move(keep);
    }
    if (src.nodes.empty() || dst.nodes.empty()) continue;
    router_.allow_crossing(&crossable_[ci], crossing_any_);
    path = router_.route(src, dst);
    if (!path.empty() || node_at_[c.nodes.front()] >= 0) break;  // a wider radius only helps unplaced ends
  }
  return path;
}

void RoutingAttempt::note_crossing(int a, int b) {
  crossable_[a][b] = crossable_[b][a] = 0;
  crossed_[a].push_back(b);
  crossed_[b].push_back(a);
}

// Puts chain ci's path on the grid: its ends placed, its nodes, diagonals and ports taken,
// the crossings on it noted.
void RoutingAttempt::commit(int ci, const std::vector<int>& path) {
  const auto& c = chains_[ci];
  int first = path.front(), last = path.back();
  for (auto [v, node] : {std::pair{c.nodes.front(), first}, std::pair{c.nodes.back(), last}})
    if (node_at_[v] < 0) place(v, node);
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    const int node = path[i];
    const int din = direction_between(grid_, path[i - 1], node), dout = direction_between(grid_, node, path[i + 1]);
    const auto axis = static_cast<std::int8_t>(din == dout ? din % 4 : -1);
    if (grid_.used[node] == kPath) {  // crossing another path
      grid_.used[node] = kCrossing;
      grid_.owner2[node] = ci;
      grid_.axis2[node] = axis;
      note_crossing(ci, grid_.owner[node]);
    } else {
      grid_.used[node] = kPath;
      grid_.owner[node] = ci;
      grid_.axis[node] = axis;
    }
  }
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    int d = direction_between(grid_, path[i], path[i + 1]);
    if (int other = grid_.crossing_diagonal(path[i], d); other >= 0) note_crossing(ci, other);
    grid_.take_diagonal(path[i], d, ci);
  }
  int out_port = direction_between(grid_, first, path[1]);
  int in_port = direction_between(grid_, last, path[path.size() - 2]);
  for (auto [v, port, front] : {std::tuple{c.nodes.front(), out_port, true}, std::tuple{c.nodes.back(), in_port, false}})
    if (!keeps_circular_order(anchor_ports_[v], end_angles_[v], end_angle(g_, c, front), port)) out_of_order_[ci] = true;
  port_chain_[c.nodes.front()][out_port] = ci;
  port_chain_[c.nodes.back()][in_port] = ci;
  anchor_ports_[c.nodes.front()].push_back({out_port, end_angle(g_, c, true)});
  anchor_ports_[c.nodes.back()].push_back({in_port, end_angle(g_, c, false)});
  ports_of_[ci] = {out_port, in_port};
  grid_path_[ci] = path;
}

void RoutingAttempt::release_port(std::uint32_t v, int port) {
  port_chain_[v][port] = -1;
  auto& list = anchor_ports_[v];
  list.erase(std::remove_if(list.begin(), list.end(), [port](auto e) { return e.first == port; }), list.end());
}

// Takes chain ci's path off the grid again (commit undone; the crossings it had may happen again).
void RoutingAttempt::rip_up(int ci) {
  const auto& c = chains_[ci];
  const auto& path = grid_path_[ci];
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    const int node = path[i];
    if (grid_.used[node] == kCrossing) {  // the other path stays
      if (grid_.owner[node] == ci) {
        grid_.owner[node] = grid_.owner2[node];
        grid_.axis[node] = grid_.axis2[node];
      }
      grid_.owner2[node] = -1;
      grid_.axis2[node] = -1;
      grid_.used[node] = kPath;
    } else {
      grid_.used[node] = kFree;
      grid_.owner[node] = -1;
      grid_.axis[node] = -1;
    }
  }
  for (int other : crossed_[ci]) {
    crossable_[ci][other] = crossable_[other][ci] = geo_crossing_[ci][other];
    auto& list = crossed_[other];
    list.erase(std::find(list.begin(), list.end(), ci));
  }
  crossed_[ci].clear();
  for (std::size_t i = 0; i + 1 < path.size(); ++i)
    grid_.release_diagonal(path[i], direction_between(grid_, path[i], path[i + 1]));
  release_port(c.nodes.front(), ports_of_[ci][0]);
  release_port(c.nodes.back(), ports_of_[ci][1]);
  grid_path_[ci].clear();
}

// The chains a negotiated path goes through rather than legally across, with the node.
std::vector<std::pair<int, int>> RoutingAttempt::conflicts(int ci, const std::vector<int>& path) const {
  std::vector<std::pair<int, int>> victims;
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    const int node = path[i];
    const int din = direction_between(grid_, path[i - 1], node), dout = direction_between(grid_, node, path[i + 1]);
    if (grid_.used[node] == kPath) {
      const int other = grid_.owner[node];
      const bool legal = din == dout && grid_.axis[node] >= 0 && grid_.axis[node] != din % 4 &&
                         (crossable_[ci][other] || crossing_any_);
      if (!legal) victims.push_back({other, node});
    } else if (grid_.used[node] == kCrossing) {
      victims.push_back({grid_.owner[node], node});
      victims.push_back({grid_.owner2[node], node});
    }
  }
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const int other = grid_.crossing_diagonal(path[i], direction_between(grid_, path[i], path[i + 1]));
    if (other >= 0 && !crossable_[ci][other] && !crossing_any_) victims.push_back({other, path[i]});
  }
  return victims;
}

// ---- the passes -----------------------------------------------------------------------------

// Route in order; a chain whose search was walled in rips up the paths that walled it
// and goes again before them (each chain at most a few times, rip-ups capped overall).
void RoutingAttempt::route_negotiating(const std::vector<int>& order, Clock::time_point deadline) {
  std::deque<int> work(order.begin(), order.end());
  std::size_t evictions = 0, max_evictions = p_.evictions_per_chain * chains_.size() + 16;
  history_.assign(grid_.used.size(), 0.0f);
  router_.set_history(&history_);
  while (!work.empty()) {
    int ci = work.front();
    work.pop_front();
    if (!grid_path_[ci].empty()) continue;
    util::check_stop();  // the request's own deadline or client, beyond the layout's time limit
    if (Clock::now() > deadline) {
      result_.timed_out = true;
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
    router_.set_negotiation(true);
    path = try_route(ci);
    router_.set_negotiation(false);
    if (path.empty()) continue;  // not even through others: the fallbacks below try
    auto victims = conflicts(ci, path);
    for (auto [victim, node] : victims) history_[static_cast<std::size_t>(node)] += p_.history_step;
    for (auto [victim, node] : victims) {
      if (grid_path_[victim].empty()) continue;  // already torn up (it met the path twice)
      rip_up(victim);
      work.push_back(victim);
      ++evictions;
    }
    commit(ci, path);
  }
  result_.ripups = evictions;
}

// Whatever is still walled in crosses paths it does not cross geographically...
void RoutingAttempt::route_crossing_any(Clock::time_point deadline) {
  crossing_any_ = true;
  for (std::size_t ci = 0; ci < chains_.size(); ++ci) {
    if (!grid_path_[ci].empty() || Clock::now() > deadline) continue;
    auto path = try_route(static_cast<int>(ci));
    if (path.empty()) continue;
    commit(static_cast<int>(ci), path);
    ++result_.crossing_routes;
  }
  crossing_any_ = false;
}

// ...or, as the last resort, goes through other paths rather than straight across.
void RoutingAttempt::route_overlapping() {
  router_.allow_overlap(true);
  for (std::size_t ci = 0; ci < chains_.size(); ++ci) {
    if (!grid_path_[ci].empty()) continue;
    auto path = try_route(static_cast<int>(ci));
    if (path.empty()) continue;
    ++result_.overlapping;
    const auto& c = chains_[ci];
    int out_port = direction_between(grid_, path.front(), path[1]);
    int in_port = direction_between(grid_, path.back(), path[path.size() - 2]);
    port_chain_[c.nodes.front()][out_port] = static_cast<int>(ci);
    port_chain_[c.nodes.back()][in_port] = static_cast<int>(ci);
    grid_path_[ci] = path;  // not committed to the grid: later overlap routes may cross it too
  }
  router_.allow_overlap(false);
}

// Positions: anchors from the grid (or their stretched position when never routed),
// interior stations along their chain at their share of the target length.
void RoutingAttempt::build_layout() {
  auto& L = result_.layout;
  L.pos.assign(n_, {0, 0});
  for (std::uint32_t v = 0; v < n_; ++v) L.pos[v] = node_at_[v] >= 0 ? grid_.point(node_at_[v]) : start_[v];
  L.paths.assign(g_.edges.size(), {});
  for (std::size_t ci = 0; ci < chains_.size(); ++ci) {
    const auto& c = chains_[ci];
    if (grid_path_[ci].empty()) {
      result_.failed_chains.push_back(static_cast<int>(ci));
      result_.failed += c.edges.size();
      for (std::size_t k = 1; k + 1 < c.nodes.size(); ++k) L.pos[c.nodes[k]] = start_[c.nodes[k]];
      continue;
    }
    std::vector<XY> pts;
    for (int node : grid_path_[ci]) pts.push_back(grid_.point(node));
    unroll_chain(g_, c, simplify_collinear(pts), L);
  }
  for (std::size_t ci = 0; ci < chains_.size(); ++ci)
    if (out_of_order_[ci]) result_.out_of_order_chains.push_back(static_cast<int>(ci));
  for (std::size_t e = 0; e < g_.edges.size(); ++e)
    if (L.paths[e].empty()) L.paths[e] = {L.pos[g_.edges[e].first], L.pos[g_.edges[e].second]};
}

}  // namespace tourmap::metro::octi
