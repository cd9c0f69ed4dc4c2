#pragma once
// The full route table: API routes, server routes (/metrics, the spec) and WebSocket endpoints.

#include "crowd_stream.hpp"
#include "events.hpp"
#include "server_state.hpp"

#include "api/routes.hpp"

#include <string>
#include <utility>
#include <vector>

namespace tourmap::server {

void register_routes(ServerState& state, api::AppContext& ctx, EventHub& events, CrowdStreamer& crowd);

// (method, pattern) of everything register_routes adds; WebSocket endpoints as ("WS", path).
std::vector<std::pair<std::string, std::string>> registered_routes();

}  // namespace tourmap::server
