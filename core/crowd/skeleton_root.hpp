#pragma once
// The main root joint of a skeleton: among joints without a parent, the one with the most
// descendant joints (a character's hips rather than, say, a stray IK target).

#include <cstddef>
#include <vector>

namespace tourmap::crowd {

// -1 for an empty skeleton.
inline int main_root_joint(const std::vector<int>& parent) {
  std::vector<int> descendants(parent.size(), 0);
  for (std::size_t j = 0; j < parent.size(); ++j) {
    std::size_t steps = 0;  // a malformed parent array could loop; a chain is never longer than n
    for (int p = parent[j]; p >= 0 && static_cast<std::size_t>(p) < parent.size() && steps < parent.size();
         p = parent[static_cast<std::size_t>(p)], ++steps)
      ++descendants[static_cast<std::size_t>(p)];
  }
  int best = -1;
  for (std::size_t j = 0; j < parent.size(); ++j)
    if (parent[j] < 0 && (best < 0 || descendants[j] > descendants[static_cast<std::size_t>(best)]))
      best = static_cast<int>(j);
  return best;
}

}  // namespace tourmap::crowd
