#pragma once
// One path through the octilinear grid graph: A* over (grid node, incoming direction) states,
// so that a bend costs what it turns (GridRouteParams::bend_cost), between candidate nodes and
// ports at both ends. What a path may pass depends on the mode: free nodes only; across a path
// it may cross (straight over, at crossing_cost / added_crossing_cost); negotiating, through
// other paths at a price that grows with the node's history (PathFinder, McMurchie and Ebeling
// 1995); as the last resort, through anything but stations at overlap_cost.

#include "metro/grid_graph.hpp"
#include "metro/octilinear_grid.hpp"

#include <array>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>

#include <boost/heap/d_ary_heap.hpp>
#include <utility>
#include <vector>

namespace tourmap::metro::octi {

// One end of a search.
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
std::vector<int> without_loops(const std::vector<int>& path);

class GridRouter {
 public:
  // `grid` and `p` must outlive the router; the grid's size must not change.
  GridRouter(GridGraph& grid, const GridRouteParams& p);

  // Cheapest path from `src` to `dst`; empty when there is none. Grid node sequence.
  std::vector<int> route(const Endpoint& src, const Endpoint& dst);

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

  // States the last search expanded (0 when its end was found walled in without one).
  std::size_t expansions() const { return expansions_; }

 private:
  using Item = std::pair<double, long>;  // f, state (>= goal_base: goal)
  // A 4-ary heap pops the same (f, state) order as a binary one, with fewer cache misses on
  // the large open lists of long routes (the search's main cost).
  using OpenList = boost::heap::d_ary_heap<Item, boost::heap::arity<4>, boost::heap::compare<std::greater<Item>>>;
  struct Arrival {
    long goal, parent;
    double total;
  };

  static double distance_to_segment(double x, double y, XY a, XY b);
  double heuristic(int node, const Endpoint& dst) const;
  double heuristic_at(int x, int y, const Endpoint& dst) const;
  bool standable(int node) const;
  bool diagonal_blocked(int node, int d) const;
  bool may_reach(const Endpoint& src, const Endpoint& dst);
  void set_corridor(const Endpoint& src, const Endpoint& dst);
  bool relax(long s, double c, long parent);
  long search(OpenList& open, const Endpoint& src, const Endpoint& dst);
  void expand(OpenList& open, long s, const Endpoint& src, const Endpoint& dst, double& best_goal);
  bool straight_on_only(int node, int din) const;
  std::optional<double> turn_price(const Endpoint& src, int din, int d) const;
  std::optional<double> diagonal_price(int node, int d) const;
  std::optional<double> occupancy_price(int next, int d) const;
  double reserved_price(int next, const Endpoint& src, const Endpoint& dst) const;
  double corridor_price(int nx, int ny) const;
  std::vector<int> trace_back(long found);
  double eviction_price(int node) const;
  double crossing_price(int other) const;

  GridGraph& grid_;
  const GridRouteParams& p_;
  const std::vector<char>* crossable_ = nullptr;
  bool cross_any_ = false;
  XY corridor_a_, corridor_b_;
  double corridor_slack_ = 0;
  bool overlap_ = false;
  bool negotiate_ = false;
  const std::vector<float>* history_ = nullptr;
  // Search state, by state (node * 9 + incoming direction); stamp != now_ means unset. One
  // record per state (one cache miss where three arrays took three), in zeroed memory from
  // calloc: a search touches a small part of the grid, and untouched pages are never mapped.
  struct StateRecord {
    double cost;
    std::int32_t parent;  // state, or -1
    std::uint32_t stamp;
  };
  struct FreeRecords {
    void operator()(StateRecord* p) const { std::free(p); }
  };
  std::unique_ptr<StateRecord[], FreeRecords> state_;
  long states_ = 0;
  std::size_t expansions_ = 0;
  std::uint32_t now_ = 0;
  std::vector<double> target_cost_;  // by grid node: the cost of ending there, or infinity
  // may_reach's visits, by grid node: reached from the source / the target side in search now_.
  std::vector<std::uint32_t> reached_src_, reached_dst_;
  std::vector<int> frontier_src_, frontier_dst_;
  std::vector<Arrival> goal_parents_;
};

}  // namespace tourmap::metro::octi
