// POST /api/v1/deform/{focus,mental,destination} request bodies: the JSON body reader the
// handlers use (parse_json_body: content type, depth cap, syntax errors) and the body
// validation (parse_deform_request), then, as DeformService does for inline networks,
// parse_inline_roads. The first byte picks the endpoint. Clean error: api::ApiError.

#include "fuzz_common.hpp"

#include "api/deform_request.hpp"
#include "api/params.hpp"
#include "api/roads_in.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap::api;
  if (size < 1) return 0;
  const DeformApp apps[] = {DeformApp::focus, DeformApp::mental, DeformApp::destination};
  const DeformApp app = apps[data[0] % 3];
  Request req;
  req.method = "POST";
  req.path = std::string("/api/v1/deform/") + app_name(app);
  req.content_type = "application/json";
  req.body.assign(reinterpret_cast<const char*>(data + 1), size - 1);
  const DeformLimits limits;
  try {
    const DeformRequest r = parse_deform_request(app, parse_json_body(req), limits);
    (void)r.grid.describe();
    if (r.roads_inline) (void)parse_inline_roads(*r.roads_inline, "roads", limits.max_inline_vertices);
  } catch (const ApiError&) {
  }
  return 0;
}
