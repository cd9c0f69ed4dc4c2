#include "poi/serialize.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <stdexcept>

namespace tourmap::poi {
namespace {

ClusterTree sample_tree(std::size_t n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-500.0, 500.0);
  std::vector<ClusterPoint> p(n);
  for (auto& q : p) q = {{u(rng), u(rng)}, u(rng) + 500};
  return build_cluster_tree(p);
}

void expect_equal(const ClusterTree& a, const ClusterTree& b) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  EXPECT_EQ(a.children, b.children);
  EXPECT_EQ(a.root, b.root);
  EXPECT_EQ(a.leaves, b.leaves);
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const auto &x = a.nodes[i], &y = b.nodes[i];
    EXPECT_EQ(std::memcmp(&x.center, &y.center, sizeof x.center), 0);
    EXPECT_EQ(x.min.x, y.min.x);
    EXPECT_EQ(x.min.y, y.min.y);
    EXPECT_EQ(x.max.x, y.max.x);
    EXPECT_EQ(x.max.y, y.max.y);
    EXPECT_EQ(x.size, y.size);
    EXPECT_EQ(x.worth, y.worth);
    EXPECT_EQ(x.representative, y.representative);
    EXPECT_EQ(x.parent, y.parent);
    EXPECT_EQ(x.first_child, y.first_child);
    EXPECT_EQ(x.child_count, y.child_count);
    EXPECT_EQ(x.level, y.level);
  }
}

TEST(PoiSerialize, RoundTrips) {
  for (std::size_t n : {0, 1, 2, 150}) {
    auto t = sample_tree(n);
    auto bytes = serialize(t);
    expect_equal(deserialize(bytes), t);
    EXPECT_EQ(serialize(deserialize(bytes)), bytes);
  }
}

TEST(PoiSerialize, RejectsCorruptInput) {
  auto bytes = serialize(sample_tree(40));
  for (std::size_t cut :
       {std::size_t{0}, std::size_t{3}, std::size_t{20}, std::size_t{47}, bytes.size() / 2, bytes.size() - 1})
    EXPECT_THROW(deserialize(std::string_view(bytes).substr(0, cut)), std::invalid_argument) << cut;
  EXPECT_THROW(deserialize(bytes + "x"), std::invalid_argument);

  auto bad_magic = bytes;
  bad_magic[0] = 'X';
  EXPECT_THROW(deserialize(bad_magic), std::invalid_argument);
  auto bad_version = bytes;
  bad_version[4] = 9;
  EXPECT_THROW(deserialize(bad_version), std::invalid_argument);
  auto huge_count = bytes;
  huge_count[16 + 7] = 0x7f;  // node count's top byte
  EXPECT_THROW(deserialize(huge_count), std::invalid_argument);
  for (std::size_t at : {std::size_t{60}, bytes.size() / 3, bytes.size() - 2}) {
    auto flipped = bytes;
    flipped[at] = static_cast<char>(flipped[at] ^ 0x10);
    EXPECT_THROW(deserialize(flipped), std::invalid_argument) << at;
  }
}

TEST(PoiSerialize, RejectsBrokenStructureWithValidChecksum) {
  auto t = sample_tree(10);
  auto cycle = t;
  cycle.children[0] = cycle.root;  // the root listed as a child
  EXPECT_THROW(deserialize(serialize(cycle)), std::invalid_argument);
  auto range = t;
  range.nodes[range.root].first_child = static_cast<std::uint32_t>(range.children.size());
  EXPECT_THROW(deserialize(serialize(range)), std::invalid_argument);
  auto root = t;
  root.root = 0;
  EXPECT_THROW(deserialize(serialize(root)), std::invalid_argument);
  auto rep = t;
  rep.nodes[rep.root].representative = 1000;
  EXPECT_THROW(deserialize(serialize(rep)), std::invalid_argument);
}

}  // namespace
}  // namespace tourmap::poi
