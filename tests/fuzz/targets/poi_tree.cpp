// Cached POI cluster trees (core/poi/serialize: poi::deserialize), the blob MetroService reads
// back from the store's result cache. The header's CRC-32 is recomputed over the body before
// the call, so mutated bodies reach the structural checks instead of stopping at the
// checksum. Accepted trees are walked the way active_clusters walks them. Clean error: std::invalid_argument.

#include "fuzz_common.hpp"

#include "poi/serialize.hpp"

#include <zlib.h>

#include <cstring>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap::poi;
  constexpr std::size_t kHeader = 4 + 4 + 8 + 8 + 8 + 4 + 4;
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (bytes.size() >= kHeader) {
    const auto crc = static_cast<std::uint32_t>(
        crc32_z(crc32_z(0, nullptr, 0), reinterpret_cast<const unsigned char*>(bytes.data() + kHeader), size - kHeader));
    std::memcpy(bytes.data() + kHeader - 4, &crc, 4);  // little-endian hosts
  }
  try {
    const ClusterTree t = deserialize(bytes);
    if (t.nodes.empty()) return 0;
    std::vector<std::uint32_t> stack{t.root};
    std::size_t visited = 0;
    while (!stack.empty()) {
      const ClusterNode& c = t.nodes.at(stack.back());
      stack.pop_back();
      FUZZ_CHECK(++visited <= t.nodes.size());
      (void)t.nodes.at(c.representative);
      for (std::uint32_t k = 0; k < c.child_count; ++k) stack.push_back(t.children.at(c.first_child + k));
    }
    FUZZ_CHECK(serialize(t) == bytes);  // round trip
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
