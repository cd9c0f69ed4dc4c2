#pragma once
// The `tourmap` command line: serve, migrate, import, routes.

namespace tourmap::server {

int run_cli(int argc, char** argv);

}  // namespace tourmap::server
