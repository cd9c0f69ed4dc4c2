#include "crowd/hierarchy_io.hpp"

#include "crowd/hierarchy_build.hpp"
#include "crowd_test_models.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>

namespace tourmap::crowd {
namespace {

const ClusterHierarchy& arm_hierarchy() {
  static const ClusterHierarchy h = [] {
    const SkinnedModel arm = test_models::make_arm();
    return build_hierarchy(arm, {}, test_models::all_poses(arm));
  }();
  return h;
}

// Byte offset of cluster i's record in serialize_hierarchy's layout (see hierarchy_io.hpp).
std::size_t cluster_offset(const ClusterHierarchy& h, std::size_t i) {
  const std::size_t header = 4 + 4 + 4 + 4 + 4 + 10 * 8 + 4 + 8 * h.stats.poses_per_animation.size() + 4 +
                             8 * h.stats.representative_poses_per_animation.size();
  return header + i * 56;
}

template <class T>
void patch(std::string& bytes, std::size_t offset, T value) {
  std::memcpy(bytes.data() + offset, &value, sizeof(T));
}

TEST(HierarchyIo, RoundTripKeepsEveryField) {
  const ClusterHierarchy& h = arm_hierarchy();
  const std::string bytes = serialize_hierarchy(h);
  const ClusterHierarchy back = deserialize_hierarchy(bytes, 656);
  ASSERT_EQ(back.clusters.size(), h.clusters.size());
  EXPECT_EQ(back.root, h.root);
  EXPECT_EQ(back.indices, h.indices);
  for (std::size_t i = 0; i < h.clusters.size(); ++i) {
    const Cluster &a = h.clusters[i], &b = back.clusters[i];
    EXPECT_EQ(a.first_index, b.first_index);
    EXPECT_EQ(a.index_count, b.index_count);
    EXPECT_EQ(a.parent, b.parent);
    EXPECT_EQ(a.children, b.children);
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.error, b.error);
    EXPECT_EQ(a.deformation_level, b.deformation_level);
    EXPECT_EQ(a.bounds.min(), b.bounds.min());
    EXPECT_EQ(a.bounds.max(), b.bounds.max());
  }
  EXPECT_EQ(back.stats.leaf_clusters, h.stats.leaf_clusters);
  EXPECT_EQ(back.stats.clusters, h.stats.clusters);
  EXPECT_EQ(back.stats.base_triangles, h.stats.base_triangles);
  EXPECT_EQ(back.stats.stored_triangles, h.stats.stored_triangles);
  EXPECT_EQ(back.stats.clusters_short_of_half, h.stats.clusters_short_of_half);
  EXPECT_EQ(back.stats.poses_per_animation, h.stats.poses_per_animation);
  EXPECT_EQ(back.stats.representative_poses_per_animation, h.stats.representative_poses_per_animation);
  EXPECT_EQ(back.stats.total_ms, h.stats.total_ms);
  EXPECT_EQ(serialize_hierarchy(back), bytes);
  std::printf("[ arm ] %zu bytes = %.1f bytes per base triangle\n", bytes.size(),
              double(bytes.size()) / double(h.stats.base_triangles));
}

TEST(HierarchyIo, EveryTruncationThrows) {
  const std::string bytes = serialize_hierarchy(arm_hierarchy());
  for (std::size_t n = 0; n < bytes.size(); ++n)
    EXPECT_THROW(deserialize_hierarchy(std::string_view(bytes).substr(0, n)), std::runtime_error) << n << " bytes";
  EXPECT_THROW(deserialize_hierarchy(bytes + '\0'), std::runtime_error);  // trailing garbage
}

TEST(HierarchyIo, CorruptFieldsThrow) {
  const ClusterHierarchy& h = arm_hierarchy();
  const std::string good = serialize_hierarchy(h);
  const std::size_t parent = static_cast<std::size_t>(h.root);
  const std::size_t leaf = static_cast<std::size_t>(h.clusters[parent].children[0]);
  auto expect_rejected = [&](const char* what, auto edit) {
    std::string bytes = good;
    edit(bytes);
    EXPECT_THROW(deserialize_hierarchy(bytes, 656), std::runtime_error) << what;
  };
  expect_rejected("magic", [](std::string& b) { b[0] = 'X'; });
  expect_rejected("version", [](std::string& b) { patch<std::uint32_t>(b, 4, 2); });
  expect_rejected("cluster count", [](std::string& b) { patch<std::uint32_t>(b, 8, 1u << 30); });
  expect_rejected("index count", [](std::string& b) { patch<std::uint32_t>(b, 12, 5); });
  expect_rejected("root out of range", [&](std::string& b) { patch<std::int32_t>(b, 16, static_cast<int>(h.clusters.size())); });
  expect_rejected("negative statistic", [](std::string& b) { patch<double>(b, 20, -1.0); });
  expect_rejected("child out of range", [&](std::string& b) { patch<std::int32_t>(b, cluster_offset(h, parent) + 12, 99999); });
  expect_rejected("child is itself", [&](std::string& b) { patch<std::int32_t>(b, cluster_offset(h, parent) + 16, static_cast<int>(parent)); });
  expect_rejected("one child", [&](std::string& b) { patch<std::int32_t>(b, cluster_offset(h, parent) + 16, -1); });
  expect_rejected("parent link", [&](std::string& b) { patch<std::int32_t>(b, cluster_offset(h, leaf) + 8, static_cast<int>(leaf)); });
  expect_rejected("depth", [&](std::string& b) { patch<std::int32_t>(b, cluster_offset(h, leaf) + 20, 0); });
  expect_rejected("index range", [&](std::string& b) { patch<std::uint32_t>(b, cluster_offset(h, leaf), 1u << 30); });
  expect_rejected("index count not x3", [&](std::string& b) { patch<std::uint32_t>(b, cluster_offset(h, leaf) + 4, 4); });
  expect_rejected("error not monotonic", [&](std::string& b) { patch<float>(b, cluster_offset(h, parent) + 24, 1e-9f); });
  expect_rejected("leaf error", [&](std::string& b) { patch<float>(b, cluster_offset(h, leaf) + 24, 0.5f); });
  expect_rejected("NaN bounds", [&](std::string& b) { patch<float>(b, cluster_offset(h, leaf) + 32, std::nanf("")); });
  expect_rejected("vertex index", [&](std::string& b) { patch<std::uint32_t>(b, b.size() - 4, 656); });
  // The same index is fine when no vertex count is given.
  std::string bytes = good;
  patch<std::uint32_t>(bytes, bytes.size() - 4, 656);
  EXPECT_NO_THROW(deserialize_hierarchy(bytes));
}

// Found by fuzz_hierarchy_io (tests/fuzz/corpus/hierarchy_io/regression-stat-cast): its
// base_triangles statistic was 3.291009114642412e+64, finite and >= 0, so it passed the check
// and was converted to size_t, which is undefined behaviour beyond size_t's range (UBSan
// float-cast-overflow). Count statistics beyond 2^53 are now refused like any corrupt field.
TEST(HierarchyIo, CountStatisticBeyondSizeTRangeThrows) {
  const std::string good = serialize_hierarchy(arm_hierarchy());
  for (std::size_t field = 0; field < 5; ++field) {  // leaf_clusters .. clusters_short_of_half
    std::string bytes = good;
    patch<double>(bytes, 20 + 8 * field, 3.291009114642412e+64);
    EXPECT_THROW(deserialize_hierarchy(bytes, 656), std::runtime_error) << "statistic " << field;
    patch<double>(bytes, 20 + 8 * field, 9007199254740992.0);  // 2^53: still a count
    EXPECT_NO_THROW(deserialize_hierarchy(bytes, 656)) << "statistic " << field;
  }
  std::string bytes = good;
  patch<double>(bytes, 20 + 8 * 5, 1e300);  // pose_selection_ms stays a double: no limit
  EXPECT_EQ(deserialize_hierarchy(bytes, 656).stats.pose_selection_ms, 1e300);
}

TEST(HierarchyIo, EmptyHierarchyRoundTrips) {
  const ClusterHierarchy empty;
  const ClusterHierarchy back = deserialize_hierarchy(serialize_hierarchy(empty));
  EXPECT_TRUE(back.clusters.empty());
  EXPECT_EQ(back.root, -1);
}

}  // namespace
}  // namespace tourmap::crowd
