#pragma once
// The cluster tree as bytes, for persisting it (SQLite blob) and reading it back: a versioned
// little-endian header (magic "TMCT", version, counts, root, CRC-32 of the body), the
// nodes field by field, then the children. Reading validates sizes, checksum and the tree
// structure, and throws std::invalid_argument on anything else.

#include "poi/cluster_tree.hpp"

#include <string>
#include <string_view>

namespace tourmap::poi {

inline constexpr std::uint32_t kClusterTreeFormat = 1;

std::string serialize(const ClusterTree& tree);
ClusterTree deserialize(std::string_view bytes);

}  // namespace tourmap::poi
