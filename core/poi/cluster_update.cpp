#include "poi/cluster_update.hpp"

#include "poi/assignment.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>

namespace tourmap::poi {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

bool valid_point(const ClusterPoint& p) {
  return std::isfinite(p.pos.x) && std::isfinite(p.pos.y) && std::isfinite(p.worth) && p.worth >= 0;
}

ClusterNode leaf_node(const ClusterPoint& p, std::uint32_t index) {
  ClusterNode leaf;
  leaf.center = leaf.min = leaf.max = p.pos;
  leaf.size = 1;
  leaf.worth = p.worth;
  leaf.representative = index;
  return leaf;
}

// The tree while it changes: member lists that differ from the tree's `children` ranges live in
// `members`; nodes that disappear are marked dead and dropped when the tree is compacted.
struct Editor {
  ClusterTree& t;
  const ClusterOptions& options;
  ClusterUpdateStats stats;
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> members;
  std::vector<char> dead;
  std::vector<char> queued;                       // per node: in `by_level`
  std::vector<char> resolve;                      // per node: members changed, re-solve its cover
  std::vector<std::vector<std::uint32_t>> by_level;  // nodes to revisit, per level

  std::vector<std::uint32_t>& own_members(std::uint32_t c) {
    auto it = members.find(c);
    if (it != members.end()) return it->second;
    const ClusterNode& n = t.nodes[c];
    auto& list = members[c];
    list.assign(t.children.begin() + n.first_child, t.children.begin() + n.first_child + n.child_count);
    return list;
  }
  std::span<const std::uint32_t> members_of(std::uint32_t c) const {
    auto it = members.find(c);
    if (it != members.end()) return it->second;
    const ClusterNode& n = t.nodes[c];
    return std::span(t.children).subspan(n.first_child, n.child_count);
  }

  void grow_flags() {
    dead.resize(t.nodes.size(), 0);
    queued.resize(t.nodes.size(), 0);
    resolve.resize(t.nodes.size(), 0);
  }
  // Revisit node c (its aggregates; its cover too when `members_changed`).
  void touch(std::uint32_t c, bool members_changed) {
    grow_flags();
    if (members_changed) resolve[c] = 1;
    if (queued[c]) return;
    queued[c] = 1;
    const std::uint32_t level = t.nodes[c].level;
    if (by_level.size() <= level) by_level.resize(level + 1);
    by_level[level].push_back(c);
  }
  void touch_parent(std::uint32_t c, bool members_changed) {
    if (t.nodes[c].parent >= 0) touch(static_cast<std::uint32_t>(t.nodes[c].parent), members_changed);
  }

  void detach(std::uint32_t c) {
    const std::int32_t p = t.nodes[c].parent;
    if (p < 0) return;
    auto& list = own_members(static_cast<std::uint32_t>(p));
    list.erase(std::find(list.begin(), list.end(), c));
    t.nodes[c].parent = -1;
    touch(static_cast<std::uint32_t>(p), true);
  }
  void attach(std::uint32_t c, std::uint32_t parent) {
    own_members(parent).push_back(c);
    t.nodes[c].parent = static_cast<std::int32_t>(parent);
    touch(parent, true);
  }

  std::uint32_t new_node(std::uint32_t level) {
    ClusterNode c;
    c.level = level;
    t.nodes.push_back(c);
    members[static_cast<std::uint32_t>(t.nodes.size() - 1)];
    grow_flags();
    return static_cast<std::uint32_t>(t.nodes.size() - 1);
  }

  // Centroid, bbox, size, worth and representative from the members (as make_node does).
  void aggregate(std::uint32_t id) {
    ClusterNode& c = t.nodes[id];
    const auto list = members_of(id);
    c.size = 0;
    c.worth = -1;
    c.min = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    c.max = {-c.min.x, -c.min.y};
    double sx = 0, sy = 0;
    for (std::uint32_t m : list) {
      const ClusterNode& child = t.nodes[m];
      sx += child.center.x * child.size;
      sy += child.center.y * child.size;
      c.size += child.size;
      c.min = {std::min(c.min.x, child.min.x), std::min(c.min.y, child.min.y)};
      c.max = {std::max(c.max.x, child.max.x), std::max(c.max.y, child.max.y)};
      if (std::tie(child.worth, c.representative) > std::tie(c.worth, child.representative) || c.worth < 0) {
        c.worth = child.worth;
        c.representative = child.representative;
      }
    }
    c.center = {std::clamp(sx / c.size, c.min.x, c.max.x), std::clamp(sy / c.size, c.min.y, c.max.y)};
  }

  // The attached leaf nearest to p: best-first over the bboxes, which stay conservative while
  // the tree changes (an insertion widens its ancestors' boxes at once).
  std::uint32_t nearest_leaf(geo::XY p) const {
    using Item = std::pair<double, std::uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    auto box_d2 = [&](std::uint32_t c) {
      const ClusterNode& n = t.nodes[c];
      const double dx = std::max({n.min.x - p.x, 0.0, p.x - n.max.x});
      const double dy = std::max({n.min.y - p.y, 0.0, p.y - n.max.y});
      return dx * dx + dy * dy;
    };
    open.emplace(box_d2(t.root), t.root);
    while (!open.empty()) {
      const auto [d, c] = open.top();
      open.pop();
      if (c < t.leaves) return c;
      for (std::uint32_t m : members_of(c)) open.emplace(box_d2(m), m);
    }
    return kNone;
  }

  void insert(std::uint32_t leaf) {
    ++stats.inserted;
    const std::uint32_t q = nearest_leaf(t.nodes[leaf].center);
    if (t.nodes[q].parent < 0) {  // a one-POI tree: the two make the root
      const std::uint32_t root = new_node(1);
      attach(q, root);
      attach(leaf, root);
      t.root = root;
      return;
    }
    const auto parent = static_cast<std::uint32_t>(t.nodes[q].parent);
    attach(leaf, parent);
    for (std::int32_t a = static_cast<std::int32_t>(parent); a >= 0; a = t.nodes[a].parent) {
      ClusterNode& n = t.nodes[a];
      const geo::XY p = t.nodes[leaf].center;
      n.min = {std::min(n.min.x, p.x), std::min(n.min.y, p.y)};
      n.max = {std::max(n.max.x, p.x), std::max(n.max.y, p.y)};
    }
  }

  // A cluster whose members changed: dissolve it, or re-solve its cover and split it.
  void revisit(std::uint32_t c) {
    std::vector<std::uint32_t>& list = own_members(c);
    const std::int32_t parent = t.nodes[c].parent;
    if (list.size() <= 1) {
      ++stats.dissolved;
      dead[c] = 1;
      if (parent >= 0) {
        auto& up = own_members(static_cast<std::uint32_t>(parent));
        auto it = std::find(up.begin(), up.end(), c);
        if (list.empty()) {
          up.erase(it);
        } else {
          *it = list[0];
          t.nodes[list[0]].parent = parent;
        }
        touch(static_cast<std::uint32_t>(parent), true);
      } else if (!list.empty()) {
        t.root = list[0];
        t.nodes[list[0]].parent = -1;
      }
      return;
    }
    if (list.size() > options.dense_limit) return;  // far beyond a local change: keep it whole
    ++stats.resolved;
    std::vector<geo::XY> centers;
    for (std::uint32_t m : list) centers.push_back(t.nodes[m].center);
    const CycleCover cover = min_cycle_cover_dense(centers);
    std::vector<std::vector<std::uint32_t>> cycles;
    std::vector<char> seen(list.size(), 0);
    for (std::size_t s = 0; s < list.size(); ++s) {
      if (seen[s]) continue;
      cycles.emplace_back();
      for (std::size_t i = s; !seen[i]; i = cover.successor[i]) {
        seen[i] = 1;
        cycles.back().push_back(list[i]);
      }
    }
    if (cycles.size() == 1) return;
    // Split: c keeps the first cycle, each other cycle becomes a cluster of the same round.
    const std::uint32_t level = t.nodes[c].level;
    std::uint32_t up = parent >= 0 ? static_cast<std::uint32_t>(parent) : kNone;
    if (up == kNone) {  // the root split: a new root above the parts
      up = new_node(level + 1);
      attach(c, up);
      t.root = up;
    }
    own_members(c) = cycles[0];  // `list` may dangle after new_node
    for (std::size_t k = 1; k < cycles.size(); ++k) {
      ++stats.split;
      const std::uint32_t part = new_node(level);
      own_members(part) = cycles[k];
      for (std::uint32_t m : cycles[k]) t.nodes[m].parent = static_cast<std::int32_t>(part);
      aggregate(part);
      attach(part, up);
    }
    touch(up, true);
  }

  // Drops dead nodes and rebuilds the flat children array from the member lists.
  void compact() {
    const std::size_t n = t.nodes.size();
    std::vector<std::uint32_t> id(n, kNone);
    std::uint32_t next = 0;
    for (std::size_t c = 0; c < n; ++c)
      if (!dead[c]) id[c] = next++;
    std::vector<std::uint32_t> children;
    children.reserve(next);
    for (std::size_t c = 0; c < n; ++c) {
      if (dead[c]) continue;
      ClusterNode node = t.nodes[c];
      const auto list = members_of(static_cast<std::uint32_t>(c));
      node.first_child = static_cast<std::uint32_t>(children.size());
      node.child_count = static_cast<std::uint32_t>(list.size());
      for (std::uint32_t m : list) children.push_back(id[m]);
      node.parent = node.parent >= 0 ? static_cast<std::int32_t>(id[node.parent]) : -1;
      t.nodes[id[c]] = node;  // id[c] <= c: nothing unread is overwritten
    }
    t.nodes.resize(next);
    t.children = std::move(children);
    t.root = id[t.root];
    members.clear();
  }
};

void validate(const ClusterTree& t, const ClusterEdits& e) {
  std::vector<char> seen(t.leaves, 0);
  auto check = [&](std::uint32_t i, const char* what) {
    if (i >= t.leaves) throw std::invalid_argument(std::string(what) + " POI " + std::to_string(i) + " is not in the tree");
    if (seen[i]) throw std::invalid_argument("POI " + std::to_string(i) + " is edited twice");
    seen[i] = 1;
  };
  for (std::uint32_t i : e.removed) check(i, "removed");
  for (const auto& [i, p] : e.changed) {
    check(i, "changed");
    if (!valid_point(p)) throw std::invalid_argument("changed POI " + std::to_string(i) + " needs a finite position and a finite worth >= 0");
  }
  for (std::size_t a = 0; a < e.added.size(); ++a)
    if (!valid_point(e.added[a]))
      throw std::invalid_argument("added POI " + std::to_string(a) + " needs a finite position and a finite worth >= 0");
  if (t.leaves - e.removed.size() + e.added.size() > 0x7fffffff)
    throw std::length_error("update_cluster_tree: too many points for 32-bit node ids");
}

// Renumbers the tree for the new POI list: kept leaves in their old order, then the added ones,
// then the clusters. Leaves of removed POIs are dropped from their clusters' member lists.
void renumber(Editor& ed, const ClusterEdits& e) {
  ClusterTree& t = ed.t;
  const std::size_t old_leaves = t.leaves, old_nodes = t.nodes.size();
  std::vector<std::uint32_t> leaf_id(old_leaves, 0);
  for (std::uint32_t i : e.removed) leaf_id[i] = kNone;
  std::uint32_t kept = 0;
  for (std::size_t i = 0; i < old_leaves; ++i)
    if (leaf_id[i] != kNone) leaf_id[i] = kept++;
  const std::size_t new_leaves = kept + e.added.size();
  const auto shift = [&](std::uint32_t c) {
    return c < old_leaves ? leaf_id[c] : static_cast<std::uint32_t>(c - old_leaves + new_leaves);
  };
  std::vector<std::uint32_t> parents_of_removed;
  for (std::uint32_t i : e.removed)
    if (t.nodes[i].parent >= 0) parents_of_removed.push_back(shift(static_cast<std::uint32_t>(t.nodes[i].parent)));

  // Leaves move left over the removed ones; clusters move by the change in the leaf count.
  for (std::size_t i = 0; i < old_leaves; ++i)
    if (leaf_id[i] != kNone && leaf_id[i] != i) t.nodes[leaf_id[i]] = t.nodes[i];
  const std::size_t clusters = old_nodes - old_leaves;
  if (new_leaves > old_leaves) {
    // Growing past the capacity copies the whole array into fresh pages (seconds' worth of page
    // faults at 10^6 POIs): leave room for the next updates too.
    if (t.nodes.capacity() < new_leaves + clusters) t.nodes.reserve(new_leaves + clusters + t.nodes.size() / 8);
    t.nodes.resize(new_leaves + clusters);
    std::move_backward(t.nodes.begin() + static_cast<std::ptrdiff_t>(old_leaves),
                       t.nodes.begin() + static_cast<std::ptrdiff_t>(old_nodes), t.nodes.end());
  } else if (new_leaves < old_leaves) {
    std::move(t.nodes.begin() + static_cast<std::ptrdiff_t>(old_leaves), t.nodes.end(),
              t.nodes.begin() + static_cast<std::ptrdiff_t>(new_leaves));
    t.nodes.resize(new_leaves + clusters);
  }
  // The slots of the added POIs hold stale copies: skipped here, written below.
  for (std::size_t i = 0; i < t.nodes.size(); ++i) {
    if (i == kept) i = new_leaves;
    if (i >= t.nodes.size()) break;
    ClusterNode& c = t.nodes[i];
    if (c.parent >= 0) c.parent = static_cast<std::int32_t>(shift(static_cast<std::uint32_t>(c.parent)));
    c.representative = leaf_id[c.representative];  // kNone for a removed POI: aggregated again
  }
  for (std::uint32_t& c : t.children) c = shift(c);  // kNone for a removed POI
  t.leaves = new_leaves;
  t.root = shift(t.root);
  for (std::size_t a = 0; a < e.added.size(); ++a)
    t.nodes[kept + a] = leaf_node(e.added[a], static_cast<std::uint32_t>(kept + a));
  ed.grow_flags();
  for (std::uint32_t p : parents_of_removed) {
    auto& list = ed.own_members(p);
    list.erase(std::remove(list.begin(), list.end(), kNone), list.end());
    ed.touch(p, true);
  }
}

}  // namespace

void permute_leaves(ClusterTree& t, const std::vector<std::uint32_t>& new_index) {
  const std::size_t n = t.leaves;
  if (new_index.size() != n) throw std::invalid_argument("permute_leaves: one new index per leaf expected");
  std::vector<char> hit(n, 0);
  for (std::uint32_t j : new_index) {
    if (j >= n || hit[j]) throw std::invalid_argument("permute_leaves: not a permutation");
    hit[j] = 1;
  }
  std::vector<ClusterNode> leaves(t.nodes.begin(), t.nodes.begin() + static_cast<std::ptrdiff_t>(n));
  for (std::size_t i = 0; i < n; ++i) {
    ClusterNode& leaf = t.nodes[new_index[i]];
    leaf = leaves[i];
    leaf.representative = new_index[i];
  }
  for (std::uint32_t& c : t.children)
    if (c < n) c = new_index[c];
  if (t.root < n) t.root = new_index[t.root];
  // Representatives bottom-up: clusters by level, the lowest index winning ties again.
  std::vector<std::uint32_t> clusters;
  for (auto id = static_cast<std::uint32_t>(n); id < t.nodes.size(); ++id) clusters.push_back(id);
  std::stable_sort(clusters.begin(), clusters.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return t.nodes[a].level < t.nodes[b].level; });
  for (std::uint32_t id : clusters) {
    ClusterNode& c = t.nodes[id];
    bool first = true;
    for (std::uint32_t a = 0; a < c.child_count; ++a) {
      const ClusterNode& child = t.nodes[t.children[c.first_child + a]];
      if (first || std::tie(child.worth, c.representative) > std::tie(c.worth, child.representative)) {
        c.worth = child.worth;
        c.representative = child.representative;
        first = false;
      }
    }
  }
}

ClusterTree copy_for_update(const ClusterTree& tree) {
  ClusterTree copy;
  copy.nodes.reserve(tree.nodes.size() + tree.nodes.size() / 8);
  copy.nodes = tree.nodes;  // keeps the capacity reserved above
  copy.children = tree.children;
  copy.root = tree.root;
  copy.leaves = tree.leaves;
  return copy;
}

ClusterUpdateStats update_cluster_tree(ClusterTree& t, const ClusterEdits& e, const ClusterOptions& options) {
  validate(t, e);
  // A tree of at most one POI, or one that keeps none in place: nothing local to do, build it.
  std::size_t moved = 0;
  for (const auto& [i, p] : e.changed) moved += p.pos.x != t.nodes[i].center.x || p.pos.y != t.nodes[i].center.y;
  if (t.leaves < 2 || e.removed.size() + moved >= t.leaves) {
    std::vector<ClusterPoint> points;
    std::vector<char> gone(t.leaves, 0);
    for (std::uint32_t i : e.removed) gone[i] = 1;
    std::unordered_map<std::uint32_t, ClusterPoint> changed(e.changed.begin(), e.changed.end());
    for (std::uint32_t i = 0; i < t.leaves; ++i) {
      if (gone[i]) continue;
      auto it = changed.find(i);
      points.push_back(it != changed.end() ? it->second : ClusterPoint{t.nodes[i].center, t.nodes[i].worth});
    }
    points.insert(points.end(), e.added.begin(), e.added.end());
    t = build_cluster_tree(points, options);
    ClusterUpdateStats stats;
    stats.rebuilt = true;
    return stats;
  }

  Editor ed{t, options, {}, {}, {}, {}, {}, {}};
  // The new index of a changed POI, before renumbering moves it.
  std::vector<std::uint32_t> removed_before(e.changed.size(), 0);
  {
    std::vector<std::uint32_t> sorted = e.removed;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 0; k < e.changed.size(); ++k)
      removed_before[k] = static_cast<std::uint32_t>(
          std::lower_bound(sorted.begin(), sorted.end(), e.changed[k].first) - sorted.begin());
  }
  const std::uint32_t first_added = static_cast<std::uint32_t>(t.leaves - e.removed.size());
  renumber(ed, e);

  std::vector<std::uint32_t> to_insert;
  for (std::size_t k = 0; k < e.changed.size(); ++k) {
    const std::uint32_t leaf = e.changed[k].first - removed_before[k];
    const ClusterPoint& p = e.changed[k].second;
    ClusterNode& n = t.nodes[leaf];
    const bool moved = n.center.x != p.pos.x || n.center.y != p.pos.y;
    n.center = n.min = n.max = p.pos;
    n.worth = p.worth;
    if (moved) {
      ed.detach(leaf);
      to_insert.push_back(leaf);
    } else {
      ed.touch_parent(leaf, false);
    }
  }
  for (std::uint32_t a = 0; a < e.added.size(); ++a) to_insert.push_back(first_added + a);
  // Every leaf that stayed attached is reachable; a cluster emptied by removals has none left.
  for (std::uint32_t leaf : to_insert) ed.insert(leaf);

  // Bottom-up: a node's parent is at a higher level, so it is revisited after it.
  for (std::uint32_t level = 1; level < ed.by_level.size(); ++level) {
    for (std::size_t k = 0; k < ed.by_level[level].size(); ++k) {
      const std::uint32_t c = ed.by_level[level][k];
      if (ed.dead[c]) continue;
      if (ed.resolve[c]) ed.revisit(c);
      if (ed.dead[c]) continue;
      ed.aggregate(c);
      ed.touch_parent(c, false);
    }
  }
  ed.compact();
  return ed.stats;
}

}  // namespace tourmap::poi
