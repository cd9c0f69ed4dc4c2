// Cached crowd cluster hierarchies (core/crowd/hierarchy_io: deserialize_hierarchy): the blob
// the crowd assets read back from the store's result cache, with the model's vertex count
// (0 = unchecked, and 656 = CesiumMan's). Accepted hierarchies are walked the way the LOD cut
// walks them and must serialize back to the same bytes. Clean error: std::runtime_error.

#include "fuzz_common.hpp"

#include "crowd/hierarchy_io.hpp"

#include <stdexcept>

namespace {

void walk(const tourmap::crowd::ClusterHierarchy& h, std::size_t vertex_count) {
  if (h.clusters.empty()) return;
  std::vector<int> stack{h.root};
  std::size_t visited = 0;
  while (!stack.empty()) {
    const auto& c = h.clusters.at(static_cast<std::size_t>(stack.back()));
    stack.pop_back();
    FUZZ_CHECK(++visited <= h.clusters.size());  // no cycle got through
    for (std::uint32_t k = 0; k < c.index_count; ++k) {
      const auto v = h.indices.at(c.first_index + k);
      FUZZ_CHECK(vertex_count == 0 || v < vertex_count);
    }
    if (!c.is_leaf()) {
      stack.push_back(c.children[0]);
      stack.push_back(c.children[1]);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap::crowd;
  const std::string_view bytes = tourmap::fuzz::as_view(data, size);
  for (std::size_t vertex_count : {std::size_t{0}, std::size_t{656}}) {
    try {
      const ClusterHierarchy h = deserialize_hierarchy(bytes, vertex_count);
      walk(h, vertex_count);
      FUZZ_CHECK(serialize_hierarchy(h).size() == bytes.size());
    } catch (const std::runtime_error&) {
    }
  }
  return 0;
}
