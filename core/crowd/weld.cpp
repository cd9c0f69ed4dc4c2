#include "crowd/weld.hpp"

#include "util/hash.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <unordered_map>

namespace tourmap::crowd {
namespace {

// Canonical bytes of a vertex's position and skinning (no padding: 12 + 8 + 16 bytes).
struct WeldKey {
  float position[3];
  std::uint16_t joint[4];
  float weight[4];
  bool operator==(const WeldKey& o) const { return std::memcmp(this, &o, sizeof(WeldKey)) == 0; }
};
static_assert(sizeof(WeldKey) == 36, "WeldKey must have no padding bytes");

struct WeldKeyHash {
  std::size_t operator()(const WeldKey& k) const {
    return static_cast<std::size_t>(util::fnv1a64(std::string_view(reinterpret_cast<const char*>(&k), sizeof(WeldKey))));
  }
};

WeldKey key_of(const SkinnedModel& m, std::size_t v, bool with_skin) {
  WeldKey k;
  std::memset(&k, 0, sizeof k);
  for (int c = 0; c < 3; ++c) k.position[c] = m.positions[v][c] + 0.0f;  // -0 -> +0
  if (!with_skin) return k;
  // Influences with weight > 0, ordered by joint, so slot order does not matter.
  std::array<std::pair<std::uint16_t, float>, 4> inf{};
  int n = 0;
  for (std::size_t s = 0; s < 4; ++s)
    if (m.weights[v][s] > 0) inf[static_cast<std::size_t>(n++)] = {m.joints[v][s], m.weights[v][s]};
  std::sort(inf.begin(), inf.begin() + n);
  for (int s = 0; s < n; ++s) {
    k.joint[s] = inf[static_cast<std::size_t>(s)].first;
    k.weight[s] = inf[static_cast<std::size_t>(s)].second;
  }
  return k;
}

}  // namespace

WeldStats weld_vertices(SkinnedModel& m, bool require_equal_skinning) {
  const std::size_t n = m.positions.size();
  if (m.normals.size() != n || m.colors.size() != n || m.joints.size() != n || m.weights.size() != n)
    throw std::invalid_argument("weld_vertices: vertex attribute arrays differ in length");
  WeldStats stats;
  stats.vertices_before = n;

  // 1. Representative (first vertex with the same key) of every vertex.
  std::unordered_map<WeldKey, std::uint32_t, WeldKeyHash> first;
  first.reserve(n);
  std::vector<std::uint32_t> rep(n);
  for (std::size_t v = 0; v < n; ++v)
    rep[v] = first.emplace(key_of(m, v, require_equal_skinning), static_cast<std::uint32_t>(v)).first->second;

  // 2. Triangles over representatives, dropping those that collapsed.
  std::vector<std::uint32_t> indices;
  indices.reserve(m.indices.size());
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    std::uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
    if (a >= n || b >= n || c >= n) throw std::invalid_argument("weld_vertices: index out of range");
    a = rep[a];
    b = rep[b];
    c = rep[c];
    if (a == b || b == c || a == c) {
      ++stats.degenerate_triangles_removed;
      continue;
    }
    indices.insert(indices.end(), {a, b, c});
  }

  // 3. Compact: keep representatives that some triangle uses, in their original order.
  std::vector<char> used(n, 0);
  for (std::uint32_t i : indices) used[i] = 1;
  std::vector<std::uint32_t> new_index(n, 0);
  std::vector<std::array<float, 4>> color_sum(n, {0, 0, 0, 0});
  std::vector<std::uint32_t> color_count(n, 0);
  for (std::size_t v = 0; v < n; ++v) {
    for (std::size_t c = 0; c < 4; ++c) color_sum[rep[v]][c] += m.colors[v][c];
    ++color_count[rep[v]];
  }
  std::size_t kept = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (!used[v]) continue;
    new_index[v] = static_cast<std::uint32_t>(kept);
    m.positions[kept] = m.positions[v];
    m.normals[kept] = m.normals[v];
    m.joints[kept] = m.joints[v];
    m.weights[kept] = m.weights[v];
    for (std::size_t c = 0; c < 4; ++c)
      m.colors[kept][c] = static_cast<std::uint8_t>(color_sum[v][c] / static_cast<float>(color_count[v]) + 0.5f);
    ++kept;
  }
  for (std::size_t v = 0; v < n; ++v)
    if (rep[v] == v && !used[v]) ++stats.unreferenced_vertices_removed;
  m.positions.resize(kept);
  m.normals.resize(kept);
  m.colors.resize(kept);
  m.joints.resize(kept);
  m.weights.resize(kept);
  for (std::uint32_t& i : indices) i = new_index[i];
  m.indices = std::move(indices);
  stats.vertices_after = kept;
  return stats;
}

}  // namespace tourmap::crowd
