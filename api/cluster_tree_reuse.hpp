#pragma once
// Cluster trees after a POI write (issue 19): a clusters request for a new city version first
// looks for the tree it last served for the same city, space and interests, and when the POIs
// differ by few additions, removals and moves, updates a copy of it (poi/cluster_update.hpp)
// instead of building from scratch. Which POI is which is found by position: a POI whose
// position is unchanged keeps its leaf (its worth may change), the rest are removals and
// additions, so a moved POI is removed and added.

#include "poi/cluster_tree.hpp"
#include "poi/cluster_update.hpp"

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace tourmap::api {

// The key without its city version ("clusters:geo:vienna@7:..." -> "clusters:geo:vienna@:..."):
// trees of one family differ only by the data version they were made for.
std::string tree_family(const std::string& key);

// `previous` updated to cluster `points` (the new POI list, in its order), or nothing when more
// than a quarter of them (at least 16) were added, removed or moved: then a rebuild is as cheap
// and does not drift.
std::optional<poi::ClusterTree> derive_tree(const poi::ClusterTree& previous, const std::vector<poi::ClusterPoint>& points,
                                            poi::ClusterUpdateStats* stats = nullptr);

// The last tree of each family, held weakly (the tree cache decides what stays in memory).
// Bounded: at most kMaxFamilies entries; past that the table starts afresh.
class LatestTrees {
 public:
  static constexpr std::size_t kMaxFamilies = 1024;
  void remember(const std::string& key, const std::shared_ptr<const poi::ClusterTree>& tree);
  // The family's last tree if it is still in memory and was made for another key.
  std::shared_ptr<const poi::ClusterTree> previous(const std::string& key) const;

 private:
  struct Entry {
    std::string key;
    std::weak_ptr<const poi::ClusterTree> tree;
  };
  mutable std::mutex mutex_;
  std::unordered_map<std::string, Entry> by_family_;
};

}  // namespace tourmap::api
