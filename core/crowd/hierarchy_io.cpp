#include "crowd/hierarchy_io.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace tourmap::crowd {
namespace {

constexpr char magic[4] = {'T', 'M', 'C', 'H'};
constexpr std::uint32_t version = 1;
constexpr std::size_t stats_fields = 10;
constexpr std::size_t cluster_bytes = 6 * 4 + 2 * 4 + 6 * 4;

static_assert(std::endian::native == std::endian::little, "hierarchy_io writes the native byte order");

class Writer {
 public:
  template <class T>
  void put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    out.append(raw, sizeof(T));
  }
  std::string out;
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : in_(bytes) {}
  template <class T>
  T get(const char* what) {
    if (in_.size() - pos_ < sizeof(T))
      throw std::runtime_error(std::string("cluster hierarchy: truncated at ") + what + " (byte " +
                               std::to_string(pos_) + " of " + std::to_string(in_.size()) + ")");
    T value;
    std::memcpy(&value, in_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  std::size_t remaining() const { return in_.size() - pos_; }

 private:
  std::string_view in_;
  std::size_t pos_ = 0;
};

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error("cluster hierarchy: " + what); }

std::string cluster_name(std::size_t i) { return "cluster " + std::to_string(i); }

}  // namespace

std::string serialize_hierarchy(const ClusterHierarchy& h) {
  Writer w;
  w.out.reserve(64 + h.clusters.size() * cluster_bytes + h.indices.size() * 4);
  w.out.append(magic, 4);
  w.put<std::uint32_t>(version);
  w.put<std::uint32_t>(static_cast<std::uint32_t>(h.clusters.size()));
  w.put<std::uint32_t>(static_cast<std::uint32_t>(h.indices.size()));
  w.put<std::int32_t>(h.root);
  const auto& s = h.stats;
  const double stats[stats_fields] = {double(s.leaf_clusters),          double(s.clusters),
                                      double(s.base_triangles),         double(s.stored_triangles),
                                      double(s.clusters_short_of_half), s.pose_selection_ms,
                                      s.clustering_ms,                  s.simplification_ms,
                                      s.total_ms,                       0.0};
  for (double v : stats) w.put<double>(v);
  for (const auto* list : {&s.poses_per_animation, &s.representative_poses_per_animation}) {
    w.put<std::uint32_t>(static_cast<std::uint32_t>(list->size()));
    for (std::size_t v : *list) w.put<std::uint64_t>(v);
  }
  for (const Cluster& c : h.clusters) {
    w.put<std::uint32_t>(c.first_index);
    w.put<std::uint32_t>(c.index_count);
    w.put<std::int32_t>(c.parent);
    w.put<std::int32_t>(c.children[0]);
    w.put<std::int32_t>(c.children[1]);
    w.put<std::int32_t>(c.depth);
    w.put<float>(c.error);
    w.put<float>(c.deformation_level);
    for (int k = 0; k < 3; ++k) w.put<float>(c.bounds.min()[k]);
    for (int k = 0; k < 3; ++k) w.put<float>(c.bounds.max()[k]);
  }
  for (std::uint32_t i : h.indices) w.put<std::uint32_t>(i);
  return std::move(w.out);
}

ClusterHierarchy deserialize_hierarchy(std::string_view bytes, std::size_t vertex_count) {
  Reader r(bytes);
  char head[4];
  for (char& ch : head) ch = r.get<char>("magic");
  if (std::memcmp(head, magic, 4) != 0) fail("bad magic (not a TMCH file)");
  const auto file_version = r.get<std::uint32_t>("version");
  if (file_version != version)
    fail("unsupported version " + std::to_string(file_version) + " (expected " + std::to_string(version) + ")");
  const auto n_clusters = r.get<std::uint32_t>("cluster count");
  const auto n_indices = r.get<std::uint32_t>("index count");
  ClusterHierarchy h;
  h.root = r.get<std::int32_t>("root");
  double stats[stats_fields];
  for (double& v : stats) {
    v = r.get<double>("stats");
    if (!std::isfinite(v) || v < 0) fail("a negative or non-finite statistic");
  }
  // The first five are counts, converted to size_t below: beyond 2^53 the conversion may be
  // undefined (and no count is that large).
  for (std::size_t i = 0; i < 5; ++i)
    if (stats[i] > 9007199254740992.0) fail("a count statistic beyond 2^53");
  auto& s = h.stats;
  s.leaf_clusters = static_cast<std::size_t>(stats[0]);
  s.clusters = static_cast<std::size_t>(stats[1]);
  s.base_triangles = static_cast<std::size_t>(stats[2]);
  s.stored_triangles = static_cast<std::size_t>(stats[3]);
  s.clusters_short_of_half = static_cast<std::size_t>(stats[4]);
  s.pose_selection_ms = stats[5];
  s.clustering_ms = stats[6];
  s.simplification_ms = stats[7];
  s.total_ms = stats[8];
  for (auto* list : {&s.poses_per_animation, &s.representative_poses_per_animation}) {
    const auto n = r.get<std::uint32_t>("animation count");
    if (n > r.remaining() / 8) fail("animation count " + std::to_string(n) + " exceeds the data");
    for (std::uint32_t i = 0; i < n; ++i) list->push_back(static_cast<std::size_t>(r.get<std::uint64_t>("pose counts")));
  }
  // Counts must match the remaining size exactly before anything is allocated.
  const std::uint64_t expected = std::uint64_t(n_clusters) * cluster_bytes + std::uint64_t(n_indices) * 4;
  if (expected != r.remaining())
    fail(std::to_string(n_clusters) + " clusters and " + std::to_string(n_indices) + " indices need " +
         std::to_string(expected) + " bytes, " + std::to_string(r.remaining()) + " remain");
  h.clusters.resize(n_clusters);
  for (Cluster& c : h.clusters) {
    c.first_index = r.get<std::uint32_t>("cluster");
    c.index_count = r.get<std::uint32_t>("cluster");
    c.parent = r.get<std::int32_t>("cluster");
    c.children[0] = r.get<std::int32_t>("cluster");
    c.children[1] = r.get<std::int32_t>("cluster");
    c.depth = r.get<std::int32_t>("cluster");
    c.error = r.get<float>("cluster");
    c.deformation_level = r.get<float>("cluster");
    Vec3 lo, hi;
    for (int k = 0; k < 3; ++k) lo[k] = r.get<float>("cluster bounds");
    for (int k = 0; k < 3; ++k) hi[k] = r.get<float>("cluster bounds");
    c.bounds = Box3(lo, hi);
  }
  h.indices.resize(n_indices);
  for (std::uint32_t& i : h.indices) i = r.get<std::uint32_t>("indices");
  validate_hierarchy(h, vertex_count);
  return h;
}

void validate_hierarchy(const ClusterHierarchy& h, std::size_t vertex_count) {
  const std::size_t n = h.clusters.size();
  if (n == 0) {
    if (h.root != -1 || !h.indices.empty()) fail("no clusters but a root or indices");
    return;
  }
  if (h.root < 0 || static_cast<std::size_t>(h.root) >= n) fail("root " + std::to_string(h.root) + " out of range");
  if (h.clusters[static_cast<std::size_t>(h.root)].parent != -1) fail("the root has a parent");
  if (vertex_count > 0)
    for (std::size_t i = 0; i < h.indices.size(); ++i)
      if (h.indices[i] >= vertex_count)
        fail("index " + std::to_string(i) + " = " + std::to_string(h.indices[i]) + " >= vertex count " +
             std::to_string(vertex_count));
  for (std::size_t i = 0; i < n; ++i) {
    const Cluster& c = h.clusters[i];
    if (c.index_count % 3 != 0) fail(cluster_name(i) + ": index count not a multiple of 3");
    if (std::uint64_t(c.first_index) + c.index_count > h.indices.size()) fail(cluster_name(i) + ": indices out of range");
    if (!std::isfinite(c.error) || c.error < 0) fail(cluster_name(i) + ": error not finite and >= 0");
    if (!std::isfinite(c.deformation_level) || c.deformation_level < 0)
      fail(cluster_name(i) + ": deformation level not finite and >= 0");
    if (c.bounds.min().hasNaN() || c.bounds.max().hasNaN()) fail(cluster_name(i) + ": NaN bounds");
    const auto [a, b] = c.children;
    if ((a < 0) != (b < 0)) fail(cluster_name(i) + ": exactly one child");
    if (a < 0) {
      if (a != -1 || b != -1) fail(cluster_name(i) + ": bad child id");
      if (c.error != 0) fail(cluster_name(i) + ": a leaf with a non-zero error");
      continue;
    }
    if (a == b || static_cast<std::size_t>(a) >= n || static_cast<std::size_t>(b) >= n || a == int(i) || b == int(i))
      fail(cluster_name(i) + ": child ids out of range or repeated");
    for (int child : {a, b}) {
      const Cluster& k = h.clusters[static_cast<std::size_t>(child)];
      if (k.parent != static_cast<int>(i)) fail(cluster_name(i) + ": child " + std::to_string(child) + " has another parent");
      if (k.error > c.error) fail(cluster_name(i) + ": error below its child's (not monotonic)");
    }
  }
  // Every cluster reached exactly once from the root, with depths counted from it.
  std::vector<char> seen(n, 0);
  std::vector<int> stack{h.root};
  std::size_t reached = 0;
  while (!stack.empty()) {
    const auto i = static_cast<std::size_t>(stack.back());
    stack.pop_back();
    if (seen[i]) fail(cluster_name(i) + " reached twice");
    seen[i] = 1;
    ++reached;
    const Cluster& c = h.clusters[i];
    const int expected_depth = c.parent < 0 ? 0 : h.clusters[static_cast<std::size_t>(c.parent)].depth + 1;
    if (c.depth != expected_depth) fail(cluster_name(i) + ": depth " + std::to_string(c.depth) + ", expected " +
                                        std::to_string(expected_depth));
    if (!c.is_leaf()) {
      stack.push_back(c.children[0]);
      stack.push_back(c.children[1]);
    }
  }
  if (reached != n) fail(std::to_string(n - reached) + " clusters not reachable from the root");
}

}  // namespace tourmap::crowd
