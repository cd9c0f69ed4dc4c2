// Inline road networks of the deform requests (api/roads_in: parse_inline_roads), read from a
// JSON body by parse_json_body as the handler does. Clean error: api::ApiError.

#include "fuzz_common.hpp"

#include "api/params.hpp"
#include "api/roads_in.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap::api;
  Request req;
  req.method = "POST";
  req.content_type = "application/json";
  req.body.assign(reinterpret_cast<const char*>(data), size);
  try {
    const auto net = parse_inline_roads(parse_json_body(req), "roads", 50000);
    // Structural promises the deformer relies on: edges join existing, distinct nodes.
    for (const auto& e : net.edges)
      FUZZ_CHECK(e.from < net.nodes.size() && e.to < net.nodes.size() && e.from != e.to);
  } catch (const ApiError&) {
  }
  return 0;
}
