#include "walk/station_walk.hpp"

#include <boost/graph/dijkstra_shortest_paths.hpp>

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <queue>

namespace tourmap::walk {
namespace {

using Vertex = std::uint32_t;

// A target snapped to the road: its vertex and the straight leg to it.
struct Candidate {
  std::uint32_t target;
  Vertex vertex;
  double leg_m;
  double straight_m;
};

// What the search knows so far: per group the best walk found (total metres, candidate), and
// the groups whose best walk can no longer improve.
struct SearchState {
  const std::multimap<Vertex, std::size_t>* at_vertex;  // vertex -> candidates there
  const std::vector<Candidate>* candidates;
  const std::vector<WalkTarget>* targets;
  const std::vector<double>* dist;
  double from_leg = 0, max_m = 0;
  std::size_t k = 0;
  std::map<std::uint32_t, std::pair<double, std::size_t>> best;  // group -> (total, candidate)
  // Totals found, smallest first; an entry whose total is within the settled radius is final
  // (every later walk is at least that long). Stale entries (a group's since-improved total)
  // count too: each group's first final entry is its best, later ones are skipped.
  std::priority_queue<std::pair<double, std::uint32_t>, std::vector<std::pair<double, std::uint32_t>>, std::greater<>>
      pending;
  std::vector<std::uint32_t> final_groups;
  std::size_t settled = 0;
};

struct StopSearch {};

// Stops the Dijkstra search (by throwing, as the Boost.Graph documentation suggests) once the
// settled radius passes the cap, or once k groups have final walks.
class StopVisitor : public boost::default_dijkstra_visitor {
 public:
  explicit StopVisitor(SearchState& s) : s_(&s) {}

  template <class Graph>
  void examine_vertex(Vertex u, const Graph&) {
    auto& s = *s_;
    ++s.settled;
    const double radius = s.from_leg + (*s.dist)[u];  // every later vertex is at least this far
    if (radius > s.max_m) throw StopSearch{};
    const auto [first, last] = s.at_vertex->equal_range(u);
    for (auto it = first; it != last; ++it) {
      const auto& c = (*s.candidates)[it->second];
      const double total = radius + c.leg_m;
      if (total > s.max_m) continue;
      const auto group = (*s.targets)[c.target].group;
      auto [slot, inserted] = s.best.try_emplace(group, total, it->second);
      if (!inserted) {
        if (total >= slot->second.first) continue;
        slot->second = {total, it->second};
      }
      s.pending.emplace(total, group);
    }
    while (!s.pending.empty() && s.pending.top().first <= radius) {
      const auto group = s.pending.top().second;
      s.pending.pop();
      if (std::find(s.final_groups.begin(), s.final_groups.end(), group) == s.final_groups.end())
        s.final_groups.push_back(group);
    }
    if (s.final_groups.size() >= s.k) throw StopSearch{};
  }

 private:
  SearchState* s_;
};

}  // namespace

WalkResult nearest_walks(const WalkGraph& g, const WalkQuery& q) {
  WalkResult out;
  if (q.k == 0 || q.targets.empty()) return out;
  const auto from = snap_to_road(g, q.from);
  if (!from.found || from.metres > q.max_snap_m) return out;
  out.from_snapped = true;
  out.from_snap_m = from.metres;

  // Only targets a straight line's length away could be reached within the cap.
  std::vector<Candidate> candidates;
  std::multimap<Vertex, std::size_t> at_vertex;
  for (std::uint32_t t = 0; t < q.targets.size(); ++t) {
    const double straight = geo::geodesic_distance_m(q.from, q.targets[t].pos);
    if (straight > q.max_m) continue;
    const auto snap = snap_to_road(g, q.targets[t].pos);
    if (!snap.found || snap.metres > q.max_snap_m) continue;
    at_vertex.emplace(snap.vertex, candidates.size());
    candidates.push_back({t, snap.vertex, snap.metres, straight});
  }
  out.candidates = candidates.size();
  if (candidates.empty()) return out;

  const std::size_t n = g.vertex_count();
  std::vector<double> dist(n);
  std::vector<Vertex> pred(n);
  SearchState state;
  state.at_vertex = &at_vertex;
  state.candidates = &candidates;
  state.targets = &q.targets;
  state.dist = &dist;
  state.from_leg = from.metres;
  state.max_m = q.max_m;
  state.k = q.k;
  try {
    boost::dijkstra_shortest_paths(
        g.graph, from.vertex,
        boost::predecessor_map(boost::make_iterator_property_map(pred.begin(), boost::get(boost::vertex_index, g.graph)))
            .distance_map(boost::make_iterator_property_map(dist.begin(), boost::get(boost::vertex_index, g.graph)))
            .weight_map(boost::get(&WalkEdgeLength::metres, g.graph))
            .visitor(StopVisitor(state)));
  } catch (const StopSearch&) {
  }
  out.settled = state.settled;

  // Every group found has its best walk now: those final when the search stopped are the
  // nearest ones; when it ran out of vertices, all of them are final.
  std::vector<std::pair<double, std::size_t>> found;  // (total, candidate)
  for (const auto& [group, best] : state.best) found.push_back(best);
  std::sort(found.begin(), found.end(), [&](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : candidates[a.second].target < candidates[b.second].target;
  });
  if (found.size() > q.k) found.resize(q.k);
  for (const auto& [total, ci] : found) {
    const auto& c = candidates[ci];
    Walk w;
    w.target = c.target;
    w.distance_m = total;
    w.straight_m = c.straight_m;
    std::vector<geo::LonLat> road;
    for (Vertex v = c.vertex;; v = pred[v]) {
      road.push_back(g.pos[v]);
      if (v == from.vertex || pred[v] == v) break;
    }
    if (from.metres > 0) w.path.push_back(q.from);
    w.path.insert(w.path.end(), road.rbegin(), road.rend());
    if (c.leg_m > 0) w.path.push_back(q.targets[c.target].pos);
    out.walks.push_back(std::move(w));
  }
  return out;
}

}  // namespace tourmap::walk
