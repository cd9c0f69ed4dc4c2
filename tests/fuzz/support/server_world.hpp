#pragma once
// The server behind the request targets (handlers, http_raw): a temporary SQLite store with a
// 5-station city ("fuzzville", POIs included) and a 3 x 3 street grid ("grid"), imported at
// start-up through the importers; a web root with a file outside it that must never be served;
// the server's full route table. The deformation limits are lowered (coarser grids, shorter
// time limits) so that one request stays well under the run's -timeout; the code paths are the
// production ones.

#include "fuzz_common.hpp"
#include "support/sample_inputs.hpp"

#include "api/routes.hpp"
#include "server/crowd_stream.hpp"
#include "server/events.hpp"
#include "server/routes_table.hpp"
#include "server/server_state.hpp"
#include "store/importer.hpp"
#include "store/migrate.hpp"

#include <boost/asio/io_context.hpp>

namespace tourmap::fuzz {

inline constexpr const char* kSecret = "tourmap-fuzz-secret-outside-the-web-root";

struct ServerWorld {
  ScratchDir& dir = ScratchDir::get();
  std::string web_root = [this] {
    std::filesystem::create_directories(dir.path() / "web" / "assets");
    dir.write("web/index.html", "<!doctype html><title>tourmap</title>");
    dir.write("web/assets/app-1234.js", "console.log('tourmap')");
    dir.write("secret.txt", kSecret);
    return (dir.path() / "web").string();
  }();
  store::DbPool pool{(dir.path() / "fuzz.db").string()};
  api::Catalog catalog{pool};
  api::DeformService deform{catalog, small_deform_limits()};
  api::MetroService metro{catalog, {}, api::MetroLimits{128, 50}};
  api::AppContext ctx{pool, catalog, deform, metro, "fuzz"};
  server::Config config = make_config(web_root);
  server::ServerState state{config};
  boost::asio::io_context ioc;
  server::EventHub events{ioc, pool, std::chrono::milliseconds(1000)};
  api::CrowdAssets assets{(dir.path() / "models").string(), nullptr};
  server::CrowdStreamer crowd{assets, ctx.crowd_limits};  // never started: no render thread

  ServerWorld() {
    {
      auto db = pool.acquire();
      store::migrate(*db);
      auto loom = dir.write("metro.json", kLoomMetro);
      auto pois = dir.write("pois.csv", kPoiCsv);
      auto osm = dir.write("grid.osm", kOsmGrid);
      store::import_metro(*db, {{"fuzzville", "Fuzzville", "hand-written"}, store::MetroFormat::loom, {loom}, false});
      store::import_pois(*db, {"fuzzville", pois, "sight", "hand-written", false});
      store::import_roads(*db, {{"grid", "Grid", "hand-written"}, osm, false});
    }
    server::register_routes(state, ctx, events, crowd);
  }

  static api::DeformLimits small_deform_limits() {
    api::DeformLimits l;
    l.max_base = 16;
    l.max_depth = 4;
    l.max_uniform = 40;
    l.max_unknowns = 20000;
    l.max_direct_grid_unknowns = 6000;
    l.max_lattice_cells = 1u << 16;
    l.max_time_limit_ms = 2000;
    return l;
  }
  static server::Config make_config(const std::string& web_root) {
    server::Config c;
    c.access_log = "off";
    c.compute_threads = 1;
    c.read_threads = 1;
    c.web_root = web_root;
    c.rate_limit = 0;  // one fuzzer, millions of requests from one address
    return c;
  }
};

}  // namespace tourmap::fuzz
