#pragma once
// The tourmap server: one listener for HTTP/1.1 and WebSocket, IO threads, the compute pool,
// and graceful shutdown on SIGINT/SIGTERM (stop accepting, finish in-flight requests within the
// drain timeout, close WebSockets with "going away", close the store).

#include "config.hpp"

#include <functional>
#include <memory>

namespace tourmap::server {

// Runs until SIGINT/SIGTERM. `on_listening(port)` is called once the socket is bound.
int serve(const Config& config, const std::function<void(unsigned short)>& on_listening = {});

}  // namespace tourmap::server
