#include "cli.hpp"
#include "cli_options.hpp"

#include "config.hpp"
#include "cors.hpp"
#include "trusted_proxies.hpp"
#include "routes_table.hpp"
#include "server.hpp"

#include "api/mip_runner.hpp"
#include "load/file.hpp"
#include "load/import_limits.hpp"
#include "load/load_error.hpp"
#include "store/city_source.hpp"
#include "store/importer.hpp"
#include "store/manifest.hpp"
#include "store/metro_rules.hpp"
#include "store/migrate.hpp"

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <thread>

#ifndef TOURMAP_VERSION
#define TOURMAP_VERSION "dev"
#endif

namespace tourmap::server {

namespace po = boost::program_options;

po::variables_map parse_options(const po::options_description& desc, const po::positional_options_description& pos,
                                const std::vector<std::string>& args) {
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(desc).positional(pos).run(), vm);
  po::store(po::parse_environment(desc,
                                  [&desc](const std::string& env) -> std::string {
                                    if (env.rfind("TOURMAP_", 0) != 0) return "";
                                    std::string name = env.substr(8);
                                    for (auto& c : name) c = c == '_' ? '-' : static_cast<char>(std::tolower(c));
                                    return desc.find_nothrow(name, false) ? name : "";
                                  }),
            vm);
  po::notify(vm);
  return vm;
}

po::options_description db_options(Config& c) {
  po::options_description d("store");
  d.add_options()("db", po::value(&c.db_path)->default_value(c.db_path), "SQLite database file (created if missing)");
  return d;
}

namespace {

constexpr const char* kUsage =
    "tourmap: interactive tourist maps (map deformation, metro maps, crowd rendering)\n"
    "\n"
    "usage: tourmap <command> [options]\n"
    "\n"
    "commands:\n"
    "  serve                     run the HTTP/WebSocket server (default port 8080)\n"
    "  migrate                   create or upgrade the database schema\n"
    "  import manifest FILE      import every city and road network a manifest lists\n"
    "  import metro FILE...      import a city's metro network (--city, --name, --format)\n"
    "  import pois FILE          import a city's POIs (--city)\n"
    "  import roads FILE         import an OSM road extract (--id, --name)\n"
    "  import city ID            a whole city from an OSM extract (--name, --osm; --gtfs, --modes):\n"
    "                            transit, POIs, roads and context in one transaction\n"
    "  keys create|list|revoke   API keys for the write endpoints (imports, deletes, cache purge)\n"
    "  routes                    list the HTTP and WebSocket routes the server registers\n"
    "\n"
    "Run `tourmap <command> --help` for the options of a command. Every option can also be set\n"
    "with an environment variable: --db is TOURMAP_DB, --port is TOURMAP_PORT, and so on.\n";

int cmd_serve(const std::vector<std::string>& args) {
  Config c = default_config();
  po::options_description desc("tourmap serve options");
  desc.add_options()("help,h", "show this help")
      ("host", po::value(&c.host)->default_value(c.host), "address to listen on (0.0.0.0 for all)")
      ("port", po::value(&c.port)->default_value(c.port), "port (0 picks a free one)")
      ("web-root", po::value(&c.web_root)->default_value(c.web_root), "directory of the built web client")
      ("data-dir", po::value(&c.data_dir)->default_value(c.data_dir),
       "sample data directory (crowd models are read from its models/)")
      ("crowd-streams", po::value(&c.max_crowd_streams)->default_value(c.max_crowd_streams),
       "concurrent crowd streams (each renders on the one render thread)")
      ("crowd-max-subdivision", po::value(&c.crowd_max_subdivision)->default_value(c.crowd_max_subdivision),
       "cap on the Loop subdivision of crowd characters (-1: the scene's; 0: base meshes, fast to prepare)")
      ("improve-mip", po::value(&c.improve_mip_s)->default_value(c.improve_mip_s),
       "CPU seconds the background MIP may take to improve a default metro layout (0: no improvements; at most 600)")
      ("io-threads", po::value(&c.io_threads)->default_value(c.io_threads), "threads for network IO")
      ("compute-threads", po::value(&c.compute_threads)->default_value(c.compute_threads),
       "threads for expensive requests: layouts, deformations, rasters, clusters, imports (0: two per core)")
      ("compute-queue", po::value(&c.compute_queue)->default_value(c.compute_queue),
       "queued compute requests before answering 503")
      ("compute-deadline", po::value(&c.compute_deadline_s)->default_value(c.compute_deadline_s),
       "seconds a request may wait for a compute thread (then 503)")
      ("compute-timeout", po::value(&c.compute_timeout_s)->default_value(c.compute_timeout_s),
       "seconds a computation may run before it is stopped (503)")
      ("max-compute-per-client", po::value(&c.max_compute_per_client)->default_value(c.max_compute_per_client),
       "compute requests a client address may have queued or running (429 beyond; 0: no cap)")
      ("read-threads", po::value(&c.read_threads)->default_value(c.read_threads),
       "threads for cheap reads (catalog, metro, POIs, roads), apart from the compute threads")
      ("read-queue", po::value(&c.read_queue)->default_value(c.read_queue), "queued reads before answering 503")
      ("read-deadline", po::value(&c.read_deadline_s)->default_value(c.read_deadline_s),
       "seconds a read may wait for a read thread (then 503)")
      ("max-reads-per-client", po::value(&c.max_reads_per_client)->default_value(c.max_reads_per_client),
       "reads a client address may have queued or running (429 beyond; 0: no cap)")
      ("max-body", po::value(&c.max_body_bytes)->default_value(c.max_body_bytes), "request body limit (bytes)")
      ("max-upload", po::value(&c.max_upload_bytes)->default_value(c.max_upload_bytes),
       "body limit of write requests with a valid API key, e.g. imports (bytes)")
      ("max-header", po::value(&c.max_header_bytes)->default_value(c.max_header_bytes),
       "request header limit, and the limit of a chunked body's trailer (bytes, at most 61440)")
      ("max-header-fields", po::value(&c.max_header_fields)->default_value(c.max_header_fields),
       "header plus trailer fields a request may have")
      ("request-timeout", po::value(&c.request_timeout_s)->default_value(c.request_timeout_s),
       "seconds to receive a request / send a response")
      ("idle-timeout", po::value(&c.idle_timeout_s)->default_value(c.idle_timeout_s),
       "seconds a keep-alive connection may stay idle")
      ("drain-timeout", po::value(&c.drain_timeout_s)->default_value(c.drain_timeout_s),
       "seconds to finish in-flight requests on SIGINT/SIGTERM")
      ("max-ws", po::value(&c.max_ws_connections)->default_value(c.max_ws_connections),
       "concurrent WebSocket connections")
      ("rate-limit", po::value(&c.rate_limit)->default_value(c.rate_limit),
       "requests per second per client address, beyond the burst (429 with Retry-After; 0: no limit)")
      ("rate-burst", po::value(&c.rate_burst)->default_value(c.rate_burst),
       "requests a client address may make at once before --rate-limit applies")
      ("cors-origins", po::value(&c.cors_origins)->default_value(c.cors_origins),
       "comma-separated origins allowed cross-origin requests ('*': any; empty: no CORS headers)")
      ("trusted-proxies", po::value(&c.trusted_proxies)->default_value(c.trusted_proxies),
       "comma-separated proxy addresses/CIDRs whose X-Forwarded-For names the client (rate limit, log)")
      ("access-log", po::value(&c.access_log)->default_value(c.access_log), "'-' (stdout), 'off', or a file")
      ("import-limit", po::value(&c.import_limits)->composing(),
       "NAME=VALUE: an import limit for uploads (repeatable), e.g. max_pois=50000; `tourmap serve "
       "--help-limits` lists them");
  desc.add(db_options(c));
  desc.add_options()("help-limits", "list the import limits and their defaults");
  auto vm = parse_options(desc, {}, args);
  if (vm.count("help")) {
    std::cout << desc << "\n";
    return 0;
  }
  if (vm.count("help-limits")) {
    for (const auto& l : load::list_limits(load::ImportLimits{}))
      std::cout << l.name << " = " << l.value << " (" << l.unit << ")\n";
    return 0;
  }
  try {
    import_limits_of(c);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "tourmap serve: --import-limit: %s\n", e.what());
    return 2;
  }
  if (!(c.rate_limit >= 0.0) || !std::isfinite(c.rate_limit) ||
      (c.rate_limit > 0.0 && (!(c.rate_burst >= 1.0) || !std::isfinite(c.rate_burst)))) {
    std::fprintf(stderr, "tourmap serve: --rate-limit must be 0 (off) or positive, with --rate-burst at least 1\n");
    return 2;
  }
  try {
    CorsPolicy check(c.cors_origins);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "tourmap serve: --cors-origins: %s\n", e.what());
    return 2;
  }
  try {
    TrustedProxies check(c.trusted_proxies);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "tourmap serve: --trusted-proxies: %s\n", e.what());
    return 2;
  }
  if (c.max_header_bytes < 1024 || c.max_header_bytes > kMaxHeaderBytesLimit || c.max_header_fields < 8) {
    std::fprintf(stderr, "tourmap serve: --max-header must be 1024 to %zu bytes and --max-header-fields at least 8\n",
                 kMaxHeaderBytesLimit);
    return 2;
  }
  if (!(c.compute_deadline_s > 0) || !(c.compute_timeout_s > 0) || !(c.read_deadline_s > 0)) {
    std::fprintf(stderr, "tourmap serve: --compute-deadline, --compute-timeout and --read-deadline must be positive\n");
    return 2;
  }
  if (!(c.improve_mip_s >= 0 && c.improve_mip_s <= 600)) {
    std::fprintf(stderr, "tourmap serve: --improve-mip must be 0 (off) to 600 seconds\n");
    return 2;
  }
  if (c.compute_threads == 0) c.compute_threads = 2 * std::max(1u, std::thread::hardware_concurrency());
  if (c.read_threads == 0) c.read_threads = 1;
  if (c.io_threads == 0) c.io_threads = 1;
  if (!std::filesystem::is_directory(c.web_root))
    std::fprintf(stderr, "warning: web root %s does not exist; only the API is served\n", c.web_root.c_str());
  return serve(c);
}

int cmd_migrate(const std::vector<std::string>& args) {
  Config c = default_config();
  po::options_description desc("tourmap migrate options");
  desc.add_options()("help,h", "show this help");
  desc.add(db_options(c));
  auto vm = parse_options(desc, {}, args);
  if (vm.count("help")) {
    std::cout << desc << "\n";
    return 0;
  }
  store::Db db(c.db_path);
  auto applied = store::migrate(db);
  for (const auto& name : applied) std::printf("applied %s\n", name.c_str());
  std::printf("schema version %d (%zu applied now)\n", store::schema_version(db), applied.size());
  return 0;
}

void print_result(const store::ImportResult& r) {
  if (r.skipped)
    std::printf("  %-6s %-20s unchanged since the last import (version %lld); use --force to re-import\n",
                r.kind.c_str(), r.target.c_str(), static_cast<long long>(r.version));
  else
    std::printf("  %-6s %-20s %s in %.2f s (version %lld)\n", r.kind.c_str(), r.target.c_str(), r.summary.c_str(),
                r.seconds, static_cast<long long>(r.version));
  for (const auto& warning : r.warnings) std::printf("         warning: %s\n", warning.c_str());
  std::fflush(stdout);
}

// A JSON file holding one rules object (store/metro_rules.hpp).
load::MetroRules read_rules(const std::string& path) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(load::read_file(path));
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(path + ": not valid JSON: " + e.what());
  }
  return store::parse_metro_rules(j, path + ": rules");
}

int cmd_import(const std::vector<std::string>& args) {
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::printf("usage: tourmap import manifest|metro|pois|roads [options] FILE...\n"
                "       tourmap import city ID --name NAME --osm EXTRACT [--gtfs FEED] [--modes MODE...]\n");
    return args.empty() ? 2 : 0;
  }
  std::string what = args[0];
  std::vector<std::string> rest(args.begin() + 1, args.end());
  Config c = default_config();
  std::vector<std::string> files;
  std::string city, name, format = "loom", attribution, category, id, rules_file, osm, gtfs;
  std::vector<std::string> modes;
  bool force = false;
  po::options_description desc("tourmap import " + what + " options");
  desc.add_options()("help,h", "show this help")("force", po::bool_switch(&force), "import even if unchanged")(
      "file", po::value(&files)->multitoken(), "input file(s)");
  if (what == "manifest")
    desc.add_options()("data-dir", po::value(&c.data_dir)->default_value(c.data_dir),
                       "directory the manifest's relative paths start from");
  if (what == "metro")
    desc.add_options()("city", po::value(&city)->required(), "city id (lower-case slug)")(
        "name", po::value(&name)->required(), "city name")(
        "format", po::value(&format)->default_value(format),
        "loom | station-csvs (stations, lines, connections) | line-csv | osm (an extract's route relations)")(
        "modes", po::value(&modes)->multitoken(),
        "osm: transit modes (subway light_rail tram train monorail funicular bus trolleybus ferry); default: the rail modes present, else bus")(
        "attribution", po::value(&attribution), "data attribution shown with the city")(
        "rules", po::value(&rules_file), "JSON file of name and line rules, as a manifest's metro \"rules\"");
  if (what == "pois")
    desc.add_options()("city", po::value(&city)->required(), "city id")(
        "category", po::value(&category), "category for POIs whose source has none")(
        "attribution", po::value(&attribution), "data attribution shown with the POIs");
  if (what == "roads")
    desc.add_options()("id", po::value(&id)->required(), "road network id (lower-case slug)")(
        "name", po::value(&name)->required(), "road network name")(
        "attribution", po::value(&attribution)->default_value("© OpenStreetMap contributors (ODbL 1.0)"),
        "data attribution");
  if (what == "city")
    desc.add_options()("name", po::value(&name)->required(), "city name")(
        "osm", po::value(&osm)->required(),
        "OSM extract (.osm, .osm.gz, .osm.bz2, .osm.pbf): transit routes, POIs, roads and context layers")(
        "gtfs", po::value(&gtfs), "GTFS feed (zip or folder): the transit network instead of the extract's routes")(
        "modes", po::value(&modes)->multitoken(),
        "transit modes (subway light_rail tram train monorail funicular bus trolleybus ferry); default: the rail modes present, else bus")(
        "attribution", po::value(&attribution), "attribution of the transit data (default: OpenStreetMap's)");
  if (what != "manifest" && what != "metro" && what != "pois" && what != "roads" && what != "city") {
    std::fprintf(stderr, "tourmap import: unknown kind '%s' (manifest, metro, pois, roads, city)\n", what.c_str());
    return 2;
  }
  desc.add(db_options(c));
  po::positional_options_description pos;
  pos.add("file", -1);
  po::variables_map vm;
  try {
    vm = parse_options(desc, pos, rest);
  } catch (const po::error& e) {
    std::fprintf(stderr, "tourmap import %s: %s\n", what.c_str(), e.what());
    return 2;
  }
  if (vm.count("help")) {
    std::cout << desc << "\n";
    return 0;
  }
  if (files.empty()) {
    std::fprintf(stderr, "tourmap import %s: %s\n", what.c_str(), what == "city" ? "no city id" : "no input file");
    return 2;
  }
  if (what == "city" && files.size() != 1) {
    std::fprintf(stderr, "tourmap import city: give one city id (the sources are --osm and --gtfs)\n");
    return 2;
  }

  store::Db db(c.db_path);
  store::migrate(db);
  if (what == "manifest") {
    if (files.size() != 1) {
      std::fprintf(stderr, "tourmap import manifest: give one manifest file\n");
      return 2;
    }
    auto manifest = store::parse_manifest(load::read_file(files[0]), c.data_dir);
    std::printf("importing %zu metro networks, %zu POI sets, %zu road networks and %zu whole cities from %s\n",
                manifest.metros.size(), manifest.pois.size(), manifest.roads.size(), manifest.sources.size(),
                c.data_dir.c_str());
    store::run_manifest(db, manifest, force, print_result);
  } else if (what == "metro") {
    store::MetroImport import{{city, name, attribution}, store::parse_metro_format(format), files, force};
    if (!rules_file.empty()) import.rules = read_rules(rules_file);
    import.modes = modes;
    print_result(store::import_metro(db, import));
  } else if (what == "city") {
    store::CitySourceImport import{{files[0], name, attribution}, osm, gtfs, "", modes, force};
    import.progress = [](const store::ImportProgress& p) {
      std::printf("  [%d/%d] %s\n", p.step, p.steps, p.stage.c_str());
      std::fflush(stdout);
    };
    for (const auto& r : store::import_city_source(db, import)) print_result(r);
  } else if (what == "pois") {
    if (files.size() != 1) throw std::invalid_argument("give one POI file");
    print_result(store::import_pois(db, {city, files[0], category, attribution, force}));
  } else {
    if (files.size() != 1) throw std::invalid_argument("give one OSM file");
    print_result(store::import_roads(db, {{id, name, attribution}, files[0], force}));
  }
  return 0;
}

int cmd_routes() {
  for (const auto& [method, pattern] : registered_routes()) std::printf("%s %s\n", method.c_str(), pattern.c_str());
  return 0;
}

}  // namespace

int run_cli(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::fputs(kUsage, stdout);
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::printf("tourmap %s\n", TOURMAP_VERSION);
    return 0;
  }
  std::string cmd = args[0];
  std::vector<std::string> rest(args.begin() + 1, args.end());
  try {
    if (cmd == "serve") return cmd_serve(rest);
    if (cmd == "migrate") return cmd_migrate(rest);
    if (cmd == "import") return cmd_import(rest);
    if (cmd == "keys") return cmd_keys(rest);
    if (cmd == "routes") return cmd_routes();
    if (cmd == "solve-mip" && rest.size() == 2)  // internal: the layout service's MIP child process
      return api::solve_mip_from_stdin(std::stod(rest[0]), std::stod(rest[1]));
  } catch (const po::error& e) {
    std::fprintf(stderr, "tourmap %s: %s\n", cmd.c_str(), e.what());
    return 2;
  } catch (const load::LoadError& e) {
    std::fprintf(stderr, "tourmap %s: import failed, nothing was changed: %s\n", cmd.c_str(), e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tourmap %s: %s\n", cmd.c_str(), e.what());
    return 1;
  }
  std::fprintf(stderr, "tourmap: unknown command '%s'\n\n%s", cmd.c_str(), kUsage);
  return 2;
}

}  // namespace tourmap::server
