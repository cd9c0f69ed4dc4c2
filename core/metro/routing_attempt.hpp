#pragma once
// One attempt of route_octilinear (metro/octilinear_grid.hpp) on one grid: every anchor placed
// on the grid first, then the chains routed one after another, breadth-first from the busiest
// anchor, negotiating when walled in (PathFinder, McMurchie and Ebeling 1995), then the
// fallbacks (crossing any path, then overlapping), and finally the stations put back along
// their chains. route_octilinear runs a few attempts and keeps the best.

#include "metro/grid_chains.hpp"
#include "metro/grid_graph.hpp"
#include "metro/grid_router.hpp"
#include "metro/octilinear_grid.hpp"

#include <array>
#include <chrono>
#include <cstdint>
#include <utility>
#include <vector>

namespace tourmap::metro::octi {

using Clock = std::chrono::steady_clock;

struct AttemptResult {
  Layout layout;
  std::size_t ripups = 0;
  std::size_t overlapping = 0;      // chains routed through other paths
  std::size_t crossing_routes = 0;  // chains that cross paths they do not cross geographically
  std::size_t failed = 0;           // edges
  std::vector<int> failed_chains;
  std::vector<int> out_of_order_chains;  // left a station by a port out of its circular order
  std::size_t grid_nodes = 0;
  bool timed_out = false;
};

class RoutingAttempt {
 public:
  // `start`: stretched positions (layout units); `chains` and `anchor` from contract_chains;
  // geo_crossing[a][b]: chains a and b cross geographically (so they may cross once in the
  // layout). Every argument must outlive the attempt. The grid has spacing `cell`.
  RoutingAttempt(const LayoutGraph& g, const std::vector<XY>& start, const std::vector<Chain>& chains,
                 const std::vector<bool>& anchor, const std::vector<std::vector<char>>& geo_crossing,
                 const GridRouteParams& p, double cell);

  // Routes every chain, those in `first` (that failed last time) first; gives up on the
  // chains still unrouted at `deadline` (they are drawn straight). Once per attempt.
  AttemptResult run(const std::vector<int>& first, Clock::time_point deadline);

 private:
  // Placement of the anchors.
  XY in_cells(XY q) const;
  void place(std::uint32_t v, int node);
  int anchor_node_near(XY c) const;
  void place_anchors();
  // The order of the chains.
  std::vector<std::vector<int>> chains_at_anchors() const;
  std::vector<int> routing_order(const std::vector<int>& first) const;
  // The ends of a search.
  Endpoint endpoint(std::uint32_t v, int chain_id, bool front, int radius) const;
  void add_candidate_nodes(Endpoint& ep, std::uint32_t v, int radius) const;
  void set_port_costs(Endpoint& ep, std::uint32_t v, int chain_id, bool front) const;
  double line_bend_cost(std::uint32_t v, int chain_id, int d) const;
  // Paths on the grid.
  std::vector<int> try_route(int ci);
  void note_crossing(int a, int b);
  void commit(int ci, const std::vector<int>& path);
  void release_port(std::uint32_t v, int port);
  void rip_up(int ci);
  std::vector<std::pair<int, int>> conflicts(int ci, const std::vector<int>& path) const;
  // The passes, in order.
  void route_negotiating(const std::vector<int>& order, Clock::time_point deadline);
  void route_crossing_any(Clock::time_point deadline);
  void route_overlapping();
  void build_layout();

  const LayoutGraph& g_;
  const std::vector<XY>& start_;
  const std::vector<Chain>& chains_;
  const std::vector<bool>& anchor_;
  const std::vector<std::vector<char>>& geo_crossing_;
  const GridRouteParams& p_;
  const std::size_t n_;  // stations
  GridGraph grid_;
  GridRouter router_;
  AttemptResult result_;

  std::vector<int> node_at_;                            // grid node of each placed anchor, or -1
  std::vector<std::array<int, 8>> port_chain_;          // per station and port: the chain using it, or -1
  std::vector<std::vector<std::pair<int, double>>> anchor_ports_;  // per station: (port, geo angle) in use
  std::vector<std::array<int, 2>> planned_;             // per chain: planned port at front / back anchor
  std::vector<std::vector<double>> end_angles_;         // per station: geographic angles of its chains

  std::vector<std::vector<int>> grid_path_;             // per chain: its grid nodes, or empty
  std::vector<std::array<int, 2>> ports_of_;            // per chain: its ports at front / back anchor
  // Which chains each chain may still cross: those it crosses geographically, once each.
  std::vector<std::vector<char>> crossable_;
  std::vector<std::vector<int>> crossed_;               // partners of the crossings on each path
  std::vector<bool> out_of_order_;                      // per chain: ever committed out of order
  bool crossing_any_ = false;                           // fallback: any path may be crossed
  std::vector<float> history_;                          // per grid node: how often it was fought over
};

}  // namespace tourmap::metro::octi
