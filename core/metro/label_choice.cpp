#include "metro/label_choice.hpp"

#include <algorithm>
#include <numeric>

namespace tourmap::metro {

namespace {

struct Search {
  const LabelChoiceInput& in;
  std::size_t max_nodes;
  std::vector<std::vector<int>> places;    // per name: its places, cheapest first
  std::vector<std::vector<int>> clash_of;  // per place: the places it clashes with
  std::vector<int> blocked;                // per place: chosen places that clash with it
  std::vector<int> open;                   // per name: its places not blocked
  std::vector<int> chosen;                 // per name: -1 until chosen
  std::size_t nodes = 0;
  bool out_of_nodes = false;

  // The unchosen name with the fewest open places (-1: all chosen).
  int next_name() const {
    int best = -1;
    for (std::size_t k = 0; k < in.names; ++k)
      if (chosen[k] < 0 && (best < 0 || open[k] < open[static_cast<std::size_t>(best)])) best = static_cast<int>(k);
    return best;
  }
  // Takes place p (block = +1) or gives it back (-1); false when taking it leaves an unchosen
  // name without an open place.
  bool take(int p, int block) {
    bool alive = true;
    for (int q : clash_of[static_cast<std::size_t>(p)]) {
      auto& b = blocked[static_cast<std::size_t>(q)];
      const std::size_t owner = in.owner[static_cast<std::size_t>(q)];
      if (block > 0 && b++ == 0) --open[owner];
      if (block < 0 && --b == 0) ++open[owner];
      if (block > 0 && chosen[owner] < 0 && open[owner] == 0) alive = false;
    }
    return alive;
  }
  bool run() {
    const int k = next_name();
    if (k < 0) return true;
    const auto name = static_cast<std::size_t>(k);
    for (int p : places[name]) {
      if (blocked[static_cast<std::size_t>(p)] > 0) continue;
      if (++nodes > max_nodes) {
        out_of_nodes = true;
        return false;
      }
      chosen[name] = p;
      const bool alive = take(p, +1);
      if (alive && run()) return true;
      take(p, -1);
      chosen[name] = -1;
      if (out_of_nodes) return false;
    }
    return false;
  }
};

}  // namespace

LabelChoice choose_label_places(const LabelChoiceInput& in, std::size_t max_nodes) {
  LabelChoice out;
  const std::size_t n = in.owner.size();
  Search s{in, max_nodes, std::vector<std::vector<int>>(in.names), std::vector<std::vector<int>>(n),
           std::vector<int>(n, 0), std::vector<int>(in.names, 0), std::vector<int>(in.names, -1)};
  if (in.cost.size() != n) {
    out.status = "none";
    return out;
  }
  std::vector<int> by_cost(n);
  std::iota(by_cost.begin(), by_cost.end(), 0);
  std::stable_sort(by_cost.begin(), by_cost.end(), [&](int a, int b) { return in.cost[static_cast<std::size_t>(a)] < in.cost[static_cast<std::size_t>(b)]; });
  for (int p : by_cost)
    if (in.owner[static_cast<std::size_t>(p)] < in.names) {
      s.places[in.owner[static_cast<std::size_t>(p)]].push_back(p);
      ++s.open[in.owner[static_cast<std::size_t>(p)]];
    }
  for (auto [a, b] : in.clashes) {
    if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= n || static_cast<std::size_t>(b) >= n) continue;
    s.clash_of[static_cast<std::size_t>(a)].push_back(b);
    s.clash_of[static_cast<std::size_t>(b)].push_back(a);
  }
  const bool found = s.run();
  out.nodes = s.nodes;
  out.status = found ? "found" : s.out_of_nodes ? "node_limit" : "none";
  if (found) out.place = s.chosen;
  return out;
}

}  // namespace tourmap::metro
