#pragma once
// One place per name for a few crowded stations at once: the names in a neighbourhood, their
// places (those clear of lines, symbols and the names outside it), and the pairs of places that
// cannot both be taken. Finds one place for every name, no two that clash, trying each name's
// places in the order of their cost: a constraint search (depth first, the name with the fewest
// places left first, places that clash with a choice struck from the others at once), exact
// within its node limit (metro/station_labels.cpp uses it where a name is still left out: the
// greedy placement with one-step repairs misses arrangements that move several names at once).
//
// Written here rather than handed to CBC (metro/mip_model.hpp) as a 0-1 program: CBC 2.10's C
// interface failed on these models ("ClpModel::getColumnName, Illegal index", no solution
// returned) and took 50-500 ms each where the search takes well under one.

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tourmap::metro {

struct LabelChoiceInput {
  std::size_t names = 0;
  std::vector<std::uint32_t> owner;          // per place: its name, 0..names-1
  std::vector<double> cost;                  // per place: tried in this order per name, lowest first
  std::vector<std::pair<int, int>> clashes;  // places that cannot both be taken
};

struct LabelChoice {
  std::string status;       // "found", "none" (no arrangement exists), "node_limit"
  std::vector<int> place;   // per name: the place taken; empty unless found
  std::size_t nodes = 0;    // search nodes visited
};

LabelChoice choose_label_places(const LabelChoiceInput& in, std::size_t max_nodes);

}  // namespace tourmap::metro
