// The write endpoints: import a city's metro network or POIs, import a road network, delete
// either, purge the result cache. The router marks them Access::api_key, so the server has
// checked the caller's API key (from the header, before reading the body) when they run. Each
// import is one transaction (store/importer.hpp): a body that fails to load changes nothing.

#include "multipart.hpp"
#include "params.hpp"
#include "routes.hpp"
#include "upload.hpp"

#include "load/load_error.hpp"
#include "store/city_source.hpp"
#include "store/importer.hpp"
#include "store/metro_rules.hpp"
#include "store/repo.hpp"

namespace tourmap::api {

namespace {

constexpr std::size_t kMaxTextParam = 500;

// An optional free-text query parameter (a name or an attribution), at most kMaxTextParam bytes.
std::string text_param(const Request& req, const std::string& name, const std::string& fallback = "") {
  const auto* v = req.query_param(name);
  if (!v) return fallback;
  if (v->size() > kMaxTextParam)
    throw bad(name, "at most " + std::to_string(kMaxTextParam) + " bytes");
  return *v;
}

// Ids of what a PUT creates: an invalid one is a bad request (a read of it would be a 404).
void require_new_id(const std::string& id, const std::string& what) {
  if (!store::is_valid_id(id))
    throw ApiError(400, "invalid_parameter",
                   "id: a " + what + " id is 1 to 64 characters of a-z, 0-9, '-' and '_', starting with a letter or digit",
                   "id");
}

// ?modes=bus,tram: the transit modes of an OSM import (load/metro_osm.hpp), at most 9.
std::vector<std::string> modes_param(const Request& req) {
  static const std::vector<std::string> known = {"subway", "light_rail", "tram", "train", "monorail",
                                                 "funicular", "bus", "trolleybus", "ferry"};
  std::vector<std::string> modes;
  const auto text = text_param(req, "modes");
  for (std::size_t start = 0; start < text.size();) {
    auto end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    const auto mode = text.substr(start, end - start);
    if (std::find(known.begin(), known.end(), mode) == known.end())
      throw bad("modes", "unknown transit mode '" + mode + "' (subway, light_rail, tram, train, monorail, funicular, bus, trolleybus, ferry)");
    if (std::find(modes.begin(), modes.end(), mode) == modes.end()) modes.push_back(mode);
    start = end + 1;
  }
  return modes;
}

void require_body(const Request& req) {
  if (req.body.empty()) throw bad("body", "empty: send the source file", "invalid_body");
}

nlohmann::json import_json(const store::ImportResult& r) {
  return {{"kind", r.kind}, {"target", r.target},   {"skipped", r.skipped}, {"version", r.version},
          {"rows", r.rows}, {"seconds", r.seconds}, {"summary", r.summary}, {"warnings", r.warnings}};
}

nlohmann::json import_json(const std::vector<store::ImportResult>& results) {
  auto imports = nlohmann::json::array();
  for (const auto& r : results) imports.push_back(import_json(r));
  return {{"imports", imports}};
}

// Runs an import, mapping the loaders' and importer's errors to 4xx answers about the body:
// beyond an import limit (load/import_limits.hpp) 413 `import_limit` whose message names the
// limit and its value, other faults of the source 422.
template <class F>
Response run_import(F&& import) {
  try {
    return json_response(import_json(import()));
  } catch (const load::LimitExceeded& e) {
    throw ApiError(413, "import_limit", std::string("body: nothing was imported: ") + e.what(), "body");
  } catch (const load::LoadError& e) {
    throw ApiError(422, "invalid_source", std::string("body: nothing was imported: ") + e.what(), "body");
  } catch (const std::invalid_argument& e) {
    throw ApiError(400, "invalid_import", std::string("body: nothing was imported: ") + e.what(), "body");
  }
}

// station-csvs sends its three files as {"stations": "...", "lines": "...", "connections": "..."},
// with the city's rules (store/metro_rules.hpp) as an optional "rules" member, as in a manifest.
std::vector<std::string> station_csv_files(const nlohmann::json& body, const UploadDir& dir, const std::string& id) {
  std::vector<std::string> files;
  for (const char* part : {"stations", "lines", "connections"}) {
    if (!body.is_object() || !body.contains(part) || !body[part].is_string())
      throw bad(part,
                "missing: format=station-csvs needs a JSON body with string fields stations, lines and connections "
                "(the three CSV files)",
                "invalid_body");
    files.push_back(dir.write(id + "." + part + ".csv", body[part].get_ref<const std::string&>()));
  }
  return files;
}

Response put_metro(AppContext& ctx, Request& req) {
  const auto& id = req.param("id");
  require_new_id(id, "city");
  require_body(req);
  std::string format = text_param(req, "format", "auto");
  if (format == "auto") {
    auto first = req.body.find_first_not_of(" \t\r\n");
    format = first != std::string::npos && req.body[first] == '{' ? "loom" : "line-csv";
  }
  store::MetroImport import;
  try {
    import.format = store::parse_metro_format(format);
  } catch (const std::invalid_argument& e) {
    throw bad("format", e.what());
  }
  std::string fallback_name;
  {
    auto db = ctx.db.acquire();
    if (auto city = store::find_city(*db, id)) fallback_name = city->name;
  }
  import.city = {id, text_param(req, "name", fallback_name), text_param(req, "attribution")};
  if (import.city.name.empty())
    throw bad("name", "a new city needs a name (?name=...)");
  import.force = query_bool(req, "force", false);
  UploadDir dir;
  if (import.format == store::MetroFormat::station_csvs) {
    auto body = parse_json_body(req);
    import.files = station_csv_files(body, dir, id);
    if (body.contains("rules")) {
      try {
        import.rules = store::parse_metro_rules(body["rules"], "rules");
      } catch (const std::invalid_argument& e) {
        throw ApiError(400, "invalid_rules", std::string("body.") + e.what() + ": nothing was imported", "rules");
      }
    }
  } else if (import.format == store::MetroFormat::osm) {
    const auto extension = sniff_osm_extension(req.body);
    if (extension.empty())
      throw ApiError(415, "unsupported_format",
                     "body: not an OSM extract (expected OSM XML, .osm.gz, .osm.bz2 or .osm.pbf bytes)", "body");
    import.files = {dir.write(id + "." + extension, req.body)};
    import.modes = modes_param(req);
  } else
    import.files = {dir.write(id + (import.format == store::MetroFormat::loom ? ".geojson" : ".csv"), req.body)};
  return run_import([&] {
    auto db = ctx.db.acquire();
    return store::import_metro(*db, import, ctx.import_limits);
  });
}

// PUT /cities/{id}/source: the body is an OSM extract, or multipart/form-data with the parts
// "osm" (the extract) and "gtfs" (a zipped feed, optional).
struct SourceParts {
  std::string_view osm, gtfs;
};

SourceParts source_parts(const Request& req) {
  if (!is_multipart(req.content_type)) return {req.body, {}};
  SourceParts out;
  for (const auto& part : parse_multipart(req.body, req.content_type)) {
    std::string_view* slot = part.name == "osm" ? &out.osm : part.name == "gtfs" ? &out.gtfs : nullptr;
    if (!slot) throw bad("body", "unknown multipart part '" + part.name + "' (expected osm and gtfs)", "invalid_body");
    if (!slot->empty() || part.data.empty())
      throw bad(part.name, part.data.empty() ? "empty part" : "sent twice", "invalid_body");
    *slot = part.data;
  }
  if (out.osm.empty()) throw bad("osm", "missing: send the OSM extract as the multipart part 'osm'", "invalid_body");
  return out;
}

// Publishes a city import's stages on WS /api/v1/events as
// {"type": "import_progress", "city", "stage", "step", "steps", "detail"}.
std::function<void(const store::ImportProgress&)> progress_events(AppContext& ctx) {
  return [events = ctx.events](const store::ImportProgress& p) {
    events->publish(nlohmann::json{{"type", "import_progress"}, {"city", p.city}, {"stage", p.stage},
                                   {"step", p.step}, {"steps", p.steps}, {"detail", p.detail}}
                        .dump());
  };
}

Response put_source(AppContext& ctx, Request& req) {
  const auto& id = req.param("id");
  require_new_id(id, "city");
  require_body(req);
  const auto parts = source_parts(req);
  const auto extension = sniff_osm_extension(parts.osm);
  if (extension.empty())
    throw ApiError(415, "unsupported_format",
                   "osm: not an OSM extract (expected OSM XML, .osm.gz, .osm.bz2 or .osm.pbf bytes)", "osm");
  if (!parts.gtfs.empty() && parts.gtfs.substr(0, 4) != std::string_view("PK\x03\x04", 4))
    throw ApiError(415, "unsupported_format", "gtfs: not a zip file (send the GTFS feed zipped)", "gtfs");
  std::string fallback_name;
  {
    auto db = ctx.db.acquire();
    if (auto city = store::find_city(*db, id)) fallback_name = city->name;
  }
  store::CitySourceImport import;
  import.city = {id, text_param(req, "name", fallback_name), text_param(req, "attribution")};
  if (import.city.name.empty()) throw bad("name", "a new city needs a name (?name=...)");
  import.modes = modes_param(req);
  import.force = query_bool(req, "force", false);
  import.progress = progress_events(ctx);
  UploadDir dir;
  import.osm = dir.write(id + "." + extension, parts.osm);
  if (!parts.gtfs.empty()) import.gtfs = dir.write(id + ".gtfs.zip", parts.gtfs);
  return run_import([&] {
    auto db = ctx.db.acquire();
    return store::import_city_source(*db, import, ctx.import_limits);
  });
}

Response put_pois(AppContext& ctx, Request& req) {
  const auto& id = req.param("id");
  require_slug(id, "city");
  require_body(req);
  {
    auto db = ctx.db.acquire();
    if (!store::city_version(*db, id))
      throw ApiError(404, "not_found", "id: no city '" + id + "': import its metro network first", "id");
  }
  UploadDir dir;
  store::PoiImport import{id, dir.write(id + ".pois." + sniff_poi_extension(req.body), req.body),
                          text_param(req, "category"), text_param(req, "attribution"),
                          query_bool(req, "force", false)};
  return run_import([&] {
    auto db = ctx.db.acquire();
    return store::import_pois(*db, import, ctx.import_limits);
  });
}

Response put_roads(AppContext& ctx, Request& req) {
  const auto& id = req.param("id");
  require_new_id(id, "road network");
  require_body(req);
  auto extension = sniff_osm_extension(req.body);
  if (extension.empty())
    throw ApiError(415, "unsupported_format",
                   "body: not an OSM extract (expected OSM XML, .osm.gz, .osm.bz2 or .osm.pbf bytes)", "body");
  std::string fallback_name;
  {
    auto db = ctx.db.acquire();
    if (auto info = store::find_road_network(*db, id)) fallback_name = info->name;
  }
  store::RoadImport import;
  import.network = {id, text_param(req, "name", fallback_name),
                    text_param(req, "attribution", "© OpenStreetMap contributors (ODbL 1.0)")};
  if (import.network.name.empty())
    throw bad("name", "a new road network needs a name (?name=...)");
  import.force = query_bool(req, "force", false);
  UploadDir dir;
  import.file = dir.write(id + "." + extension, req.body);
  return run_import([&] {
    auto db = ctx.db.acquire();
    return store::import_roads(*db, import, ctx.import_limits);
  });
}

}  // namespace

void add_write_routes(Router& router, AppContext& ctx) {
  router.add_write("PUT", "/api/v1/cities/{id}/metro", Exec::heavy,
                   [&ctx](Request& req) { return put_metro(ctx, req); });
  router.add_write("PUT", "/api/v1/cities/{id}/pois", Exec::heavy,
                   [&ctx](Request& req) { return put_pois(ctx, req); });
  router.add_write("PUT", "/api/v1/cities/{id}/source", Exec::heavy,
                   [&ctx](Request& req) { return put_source(ctx, req); });
  router.add_write("PUT", "/api/v1/roads/{id}", Exec::heavy, [&ctx](Request& req) { return put_roads(ctx, req); });

  router.add_write("DELETE", "/api/v1/cities/{id}", Exec::heavy, [&ctx](Request& req) {
    const auto& id = req.param("id");
    require_slug(id, "city");
    auto db = ctx.db.acquire();
    if (!store::delete_city(*db, id)) throw not_found("id", "city", id);
    return json_response({{"deleted", {{"kind", "city"}, {"id", id}}}});
  });
  router.add_write("DELETE", "/api/v1/roads/{id}", Exec::heavy, [&ctx](Request& req) {
    const auto& id = req.param("id");
    require_slug(id, "road network");
    auto db = ctx.db.acquire();
    if (!store::delete_road_network(*db, id)) throw not_found("id", "road network", id);
    return json_response({{"deleted", {{"kind", "roads"}, {"id", id}}}});
  });

  // Persisted results only (layouts, cluster trees, crowd hierarchies): in-memory copies are
  // keyed by data version and age out; a restart drops them.
  router.add_write("DELETE", "/api/v1/cache", Exec::heavy, [&ctx](Request& req) {
    std::string kind = text_param(req, "kind");
    if (!kind.empty() && kind != "layout" && kind != "clusters" && kind != "crowd-hierarchy")
      throw bad("kind", "expected layout, clusters or crowd-hierarchy");
    auto db = ctx.db.acquire();
    auto purged = store::cache_purge(*db, kind);
    return json_response({{"purged", purged}, {"kind", kind.empty() ? nlohmann::json(nullptr) : nlohmann::json(kind)}});
  });
}

}  // namespace tourmap::api
