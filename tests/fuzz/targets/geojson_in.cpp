// GeoJSON inputs of request bodies (api/geojson_in, api/params): POST .../pois/query reads
// "within" with parse_polygons and "bbox" with parse_bbox_json; the deform bodies read
// positions with parse_position. The body goes through parse_json_body first, as in the
// handlers. Clean error: api::ApiError.

#include "fuzz_common.hpp"

#include "api/geojson_in.hpp"
#include "api/params.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap::api;
  Request req;
  req.method = "POST";
  req.content_type = "application/geo+json";
  req.body.assign(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json doc = parse_json_body(req);
    try {
      auto polys = parse_polygons(doc, "within", GeoJsonLimits{2000});
      (void)polys;
    } catch (const ApiError&) {
    }
    try {
      (void)parse_bbox_json(doc, "bbox");
    } catch (const ApiError&) {
    }
    try {
      (void)parse_position(doc, "center");
    } catch (const ApiError&) {
    }
    // The pois/query handler's shape: {"within": ..., "bbox": [...]}.
    if (doc.is_object()) {
      if (doc.contains("within")) {
        try {
          (void)parse_polygons(doc["within"], "within");
        } catch (const ApiError&) {
        }
      }
      if (doc.contains("bbox")) (void)parse_bbox_json(doc["bbox"], "bbox");
    }
  } catch (const ApiError&) {
  }
  return 0;
}
