#include "metro/octilinear_grid.hpp"

#include "metro/grid_chains.hpp"
#include "metro/layout_quality.hpp"
#include "metro/routing_attempt.hpp"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <tuple>

// The pieces, in core/metro/: grid_chains (contraction of degree-2 chains, stations put back
// along the routed paths), grid_graph (the octilinear grid), grid_router (one path through it),
// port_planning (ports in the geographic circular order), routing_attempt (one attempt on one
// grid). Here: the attempts, and the choice of the best.

namespace tourmap::metro {
namespace {

using octi::Chain;
using octi::Clock;

using EdgePairs = std::vector<std::pair<std::size_t, std::size_t>>;

// Edges that cross geographically (straight between the real positions) may cross in the
// layout too, once per pair: a network drawn with crossings (lines that pass over each other
// without a shared station) usually has no planar octilinear layout.
EdgePairs geographic_crossings(const LayoutGraph& g) {
  std::vector<std::vector<XY>> straight;
  for (const auto& [a, b] : g.edges) straight.push_back({g.pos[a], g.pos[b]});
  return crossing_path_pairs(straight, g.edges);
}

// Such an edge is a chain of its own (its ends are anchors), so that the crossing in the layout
// is between the same two edges.
std::vector<bool> anchors_at_crossings(const LayoutGraph& g, const EdgePairs& geo_pairs) {
  std::vector<bool> anchor(g.pos.size(), false);
  for (auto [e, f] : geo_pairs)
    for (auto edge : {e, f}) anchor[g.edges[edge].first] = anchor[g.edges[edge].second] = true;
  return anchor;
}

// geo_crossing[a][b]: chains a and b hold edges that cross geographically.
std::vector<std::vector<char>> chain_crossings(const LayoutGraph& g, const std::vector<Chain>& chains,
                                               const EdgePairs& geo_pairs) {
  std::vector<int> chain_of(g.edges.size(), -1);
  for (std::size_t ci = 0; ci < chains.size(); ++ci)
    for (auto e : chains[ci].edges) chain_of[e] = static_cast<int>(ci);
  std::vector<std::vector<char>> geo_crossing(chains.size(), std::vector<char>(chains.size(), 0));
  for (auto [e, f] : geo_pairs) {
    int a = chain_of[e], b = chain_of[f];
    if (a >= 0 && b >= 0 && a != b) geo_crossing[a][b] = geo_crossing[b][a] = 1;
  }
  return geo_crossing;
}

using Rank = std::tuple<std::size_t, std::size_t, std::size_t>;

// Attempts are ranked by unrouted or overlapping chains, then by added crossings (pairs
// that do not cross geographically) and stations whose edges leave in another circular order
// (or two in one direction: the later passes keep what the router gives them), then by all
// crossings.
Rank rank(const LayoutGraph& g, const EdgePairs& geo_pairs, const octi::AttemptResult& a) {
  auto pairs = crossing_path_pairs(a.layout.paths, g.edges);
  EdgePairs added;
  std::set_difference(pairs.begin(), pairs.end(), geo_pairs.begin(), geo_pairs.end(), std::back_inserter(added));
  const std::size_t order = a.failed ? 0 : count_order_violations(g, a.layout);
  return std::tuple{a.failed + a.overlapping, added.size() + order, pairs.size()};
}

}  // namespace

Layout route_octilinear(const LayoutGraph& g, const std::vector<XY>& start, const GridRouteParams& p,
                        GridRouteReport* report) {
  auto begin = Clock::now();
  auto deadline = begin + std::chrono::microseconds(static_cast<long long>(p.time_limit_ms * 1000));
  const auto geo_pairs = geographic_crossings(g);
  auto anchor = anchors_at_crossings(g, geo_pairs);
  const auto chains = octi::contract_chains(g, anchor);
  const auto geo_crossing = chain_crossings(g, chains, geo_pairs);
  octi::AttemptResult best;
  Rank best_rank;
  bool have = false;
  int used_attempt = 1;
  std::vector<int> first;
  bool order_only = false;  // the last attempt lacked nothing but the circular order somewhere
  int attempts = std::max(1, p.attempts);
  std::vector<GridRouteReport::Attempt> tried;
  bool unrouted = false;  // the last attempt left a chain unrouted (or overlapping)
  bool tried_fine = false, tried_corridor = false;
  for (int a = 1; a <= attempts; ++a) {
    // Each attempt gets its share of the time, so a hard first one leaves room for the next.
    // The first routes freely (fewest bends). The next: when a chain was left unrouted, paths
    // kept in their corridors (so that detours do not wall stations in: an edge straight across
    // the city was left unrouted on the finer grid too); when all it lacked was the circular
    // order somewhere, the same grid again, those chains first; else a grid twice as fine
    // (room in dense centres); the corridors once the finer grid was tried.
    auto share = begin + (deadline - begin) * a / attempts;
    GridRouteParams variant = p;
    const bool corridor = a > 1 && !tried_corridor && (unrouted || tried_fine);
    const bool fine = a > 1 && !corridor && !order_only && !tried_fine;
    tried_corridor = tried_corridor || corridor;
    tried_fine = tried_fine || fine;
    if (!corridor) variant.corridor_cost = 0;
    const double cell = fine ? p.cell / 2 : p.cell;
    const auto attempt_started = Clock::now();
    auto attempt = octi::RoutingAttempt(g, start, chains, anchor, geo_crossing, variant, cell).run(first, share);
    // The next attempt routes first what this one could not route, or could not route in order.
    first = attempt.failed_chains;
    first.insert(first.end(), attempt.out_of_order_chains.begin(), attempt.out_of_order_chains.end());
    auto attempt_rank = rank(g, geo_pairs, attempt);
    tried.push_back({cell, std::chrono::duration<double, std::milli>(Clock::now() - attempt_started).count(),
                     std::get<0>(attempt_rank), std::get<1>(attempt_rank), std::get<2>(attempt_rank), attempt.ripups});
    unrouted = std::get<0>(attempt_rank) > 0;
    order_only = std::get<0>(attempt_rank) == 0 && !attempt.out_of_order_chains.empty() &&
                 std::get<1>(attempt_rank) == count_order_violations(g, attempt.layout);
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
    report->attempts = std::move(tried);
  }
  return best.layout;
}

}  // namespace tourmap::metro
