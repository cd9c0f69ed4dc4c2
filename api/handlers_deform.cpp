// POST /api/v1/deform/{focus,mental,destination}: the map deformation engine (paper ch. 4).

#include "routes.hpp"

namespace tourmap::api {

void add_deform_routes(Router& router, AppContext& ctx) {
  for (auto app : {DeformApp::focus, DeformApp::mental, DeformApp::destination})
    router.add("POST", std::string("/api/v1/deform/") + app_name(app), Exec::heavy,
               [&ctx, app](Request& req) { return ctx.deform.handle(app, req); });
}

}  // namespace tourmap::api
