#include "crowd/mesh_topology.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace tourmap::crowd {
namespace {

// The influences with a positive weight, sorted by joint, as comparable (joint, weight) pairs.
std::array<std::pair<int, float>, 4> influence_key(const SkinnedModel& m, std::size_t v) {
  std::array<std::pair<int, float>, 4> key;
  key.fill({-1, 0.f});
  if (m.weights.empty()) return key;
  for (int k = 0; k < 4; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (m.weights[v][i] > 0) key[i] = {m.joints[v][i], m.weights[v][i]};
  }
  std::sort(key.begin(), key.end());
  return key;
}

}  // namespace

void require_consistent_mesh(const SkinnedModel& m) {
  const std::size_t nv = m.positions.size();
  if (m.indices.size() % 3 != 0)
    throw std::invalid_argument("model '" + m.name + "': index count " + std::to_string(m.indices.size()) +
                                " is not a multiple of 3");
  for (std::size_t i = 0; i < m.indices.size(); ++i)
    if (m.indices[i] >= nv)
      throw std::invalid_argument("model '" + m.name + "': index " + std::to_string(i) + " = " +
                                  std::to_string(m.indices[i]) + " >= vertex count " + std::to_string(nv));
  const bool no_skin_arrays = m.joints.empty() && m.weights.empty() && m.is_static();
  if (!no_skin_arrays && (m.joints.size() != nv || m.weights.size() != nv))
    throw std::invalid_argument("model '" + m.name + "': " + std::to_string(m.joints.size()) + " joint and " +
                                std::to_string(m.weights.size()) + " weight entries for " + std::to_string(nv) +
                                " vertices");
  const std::size_t nj = m.skeleton.parent.size();
  for (std::size_t v = 0; v < m.joints.size(); ++v)
    for (std::size_t k = 0; k < 4; ++k)
      if (m.weights[v][k] > 0 && m.joints[v][k] >= std::max<std::size_t>(nj, 1))
        throw std::invalid_argument("model '" + m.name + "': vertex " + std::to_string(v) + " uses joint " +
                                    std::to_string(m.joints[v][k]) + " of " + std::to_string(nj));
  for (std::size_t j = 0; j < nj; ++j) {
    // Walking up more than nj parents means a cycle.
    int p = m.skeleton.parent[j];
    for (std::size_t steps = 0; p >= 0; ++steps) {
      if (static_cast<std::size_t>(p) >= nj)
        throw std::invalid_argument("model '" + m.name + "': joint " + std::to_string(j) + " has parent " +
                                    std::to_string(p) + " out of range");
      if (steps > nj) throw std::invalid_argument("model '" + m.name + "': the skeleton has a parent cycle");
      p = m.skeleton.parent[static_cast<std::size_t>(p)];
    }
  }
}

std::vector<std::uint32_t> canonical_vertices(const SkinnedModel& m) {
  const std::size_t nv = m.positions.size();
  std::vector<std::uint32_t> order(nv);
  std::iota(order.begin(), order.end(), 0u);
  std::vector<std::array<std::pair<int, float>, 4>> keys(nv);
  for (std::size_t v = 0; v < nv; ++v) keys[v] = influence_key(m, v);
  auto less = [&](std::uint32_t a, std::uint32_t b) {
    const Vec3& pa = m.positions[a];
    const Vec3& pb = m.positions[b];
    for (int k = 0; k < 3; ++k)
      if (pa[k] != pb[k]) return pa[k] < pb[k];
    if (keys[a] != keys[b]) return keys[a] < keys[b];
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<std::uint32_t> canonical(nv);
  for (std::size_t i = 0; i < nv;) {
    std::size_t j = i + 1;
    while (j < nv && m.positions[order[j]] == m.positions[order[i]] && keys[order[j]] == keys[order[i]]) ++j;
    // Sorted by id within a group, so order[i] is the smallest id.
    for (std::size_t k = i; k < j; ++k) canonical[order[k]] = order[i];
    i = j;
  }
  return canonical;
}

}  // namespace tourmap::crowd
