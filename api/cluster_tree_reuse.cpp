#include "cluster_tree_reuse.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

namespace tourmap::api {

std::string tree_family(const std::string& key) {
  const auto at = key.find('@');
  if (at == std::string::npos) return key;
  auto end = at + 1;
  while (end < key.size() && key[end] >= '0' && key[end] <= '9') ++end;
  return key.substr(0, at + 1) + key.substr(end);
}

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// Positions compared bit for bit: a POI that did not move has exactly the same coordinates.
struct PositionHash {
  std::size_t operator()(const geo::XY& p) const {
    std::uint64_t x, y;
    std::memcpy(&x, &p.x, sizeof x);
    std::memcpy(&y, &p.y, sizeof y);
    return std::hash<std::uint64_t>()(x * 0x9e3779b97f4a7c15ull ^ y);
  }
};
struct PositionEqual {
  bool operator()(const geo::XY& a, const geo::XY& b) const { return a.x == b.x && a.y == b.y; }
};

}  // namespace

std::optional<poi::ClusterTree> derive_tree(const poi::ClusterTree& previous, const std::vector<poi::ClusterPoint>& points,
                                            poi::ClusterUpdateStats* stats) {
  const std::size_t old_n = previous.leaves;
  // Old leaves by position (a stack per position: duplicates pair up in order).
  std::unordered_map<geo::XY, std::vector<std::uint32_t>, PositionHash, PositionEqual> at;
  at.reserve(old_n);
  for (std::uint32_t i = old_n; i-- > 0;) at[previous.nodes[i].center].push_back(i);
  std::vector<std::uint32_t> old_of_new(points.size(), kNone);
  std::vector<char> kept(old_n, 0);
  poi::ClusterEdits edits;
  for (std::size_t k = 0; k < points.size(); ++k) {
    auto it = at.find(points[k].pos);
    if (it == at.end() || it->second.empty()) {
      edits.added.push_back(points[k]);
      continue;
    }
    const std::uint32_t i = it->second.back();
    it->second.pop_back();
    old_of_new[k] = i;
    kept[i] = 1;
    if (previous.nodes[i].worth != points[k].worth) edits.changed.emplace_back(i, points[k]);
  }
  for (std::uint32_t i = 0; i < old_n; ++i)
    if (!kept[i]) edits.removed.push_back(i);
  const std::size_t structural = edits.added.size() + edits.removed.size();
  if (structural > std::max<std::size_t>(16, points.size() / 4)) return std::nullopt;

  poi::ClusterTree tree = poi::copy_for_update(previous);
  const poi::ClusterUpdateStats made = poi::update_cluster_tree(tree, edits);
  if (stats) *stats = made;
  // The update numbers the kept POIs in their old order, then the added ones; the caller's list
  // has its own order.
  std::vector<std::uint32_t> leaf_of_old(old_n, kNone);
  std::uint32_t next = 0;
  for (std::uint32_t i = 0; i < old_n; ++i)
    if (kept[i]) leaf_of_old[i] = next++;
  std::vector<std::uint32_t> new_index(points.size());
  bool identity = true;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const std::uint32_t leaf = old_of_new[k] != kNone ? leaf_of_old[old_of_new[k]] : next++;
    new_index[leaf] = static_cast<std::uint32_t>(k);
    identity = identity && leaf == k;
  }
  if (!identity) poi::permute_leaves(tree, new_index);
  return tree;
}

void LatestTrees::remember(const std::string& key, const std::shared_ptr<const poi::ClusterTree>& tree) {
  std::lock_guard lock(mutex_);
  if (by_family_.size() >= kMaxFamilies) by_family_.clear();
  by_family_[tree_family(key)] = {key, tree};
}

std::shared_ptr<const poi::ClusterTree> LatestTrees::previous(const std::string& key) const {
  std::lock_guard lock(mutex_);
  auto it = by_family_.find(tree_family(key));
  if (it == by_family_.end() || it->second.key == key) return nullptr;
  return it->second.tree.lock();
}

}  // namespace tourmap::api
