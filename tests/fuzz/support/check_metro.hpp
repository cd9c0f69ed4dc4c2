#pragma once
// What every metro loader promises about the network it returns (core/load/metro_load.hpp):
// unique node ids, finite and valid coordinates, edges between known and distinct nodes; and
// what the store's UNIQUE constraints need: unique line ids. Line indices must be in range.
// A broken promise aborts (a finding).

#include "fuzz_common.hpp"

#include "model/metro.hpp"

#include <set>
#include <string>

namespace tourmap::fuzz {

inline void check_metro(const model::MetroNetwork& net) {
  std::set<std::string> ids;
  for (const auto& n : net.nodes)
    FUZZ_CHECK(geo::is_valid(n.pos) && !n.id.empty() && ids.insert(n.id).second);
  ids.clear();
  for (const auto& l : net.lines)
    FUZZ_CHECK(ids.insert(l.id).second);
  for (const auto& e : net.edges) {
    FUZZ_CHECK(e.from < net.nodes.size() && e.to < net.nodes.size() && e.from != e.to);
    for (auto l : e.lines)
      FUZZ_CHECK(l < net.lines.size());
    for (const auto& p : e.geometry)
      FUZZ_CHECK(geo::is_valid(p));
  }
}

}  // namespace tourmap::fuzz
