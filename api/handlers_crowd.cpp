// GET /api/v1/crowd/scenes: the crowd scenes, modes, stream limits and model attributions.
// The stream itself (WS /api/v1/crowd/stream) lives in server/crowd_stream.

#include "routes.hpp"

namespace tourmap::api {

void add_crowd_routes(Router& router, AppContext& ctx) {
  router.add("GET", "/api/v1/crowd/scenes", Exec::light, [&ctx](Request&) {
    auto triangles = [&ctx](const std::string& id, int count) -> long long {
      const auto* spec = crowd::find_scene_spec(id);
      return ctx.crowd && spec ? ctx.crowd->full_triangles(*spec, count) : -1;
    };
    return json_response(crowd_scenes_json(ctx.crowd_limits, triangles));
  });
}

}  // namespace tourmap::api
