#pragma once
// Repositories over the tables in migrations/: plain structs in, plain structs out. Every write
// runs in one transaction and stamps what it wrote with the id of its `imports` row.

#include "sqlite.hpp"

#include "model/city.hpp"
#include "model/context.hpp"
#include "model/road.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tourmap::store {

// One import, as recorded in the `imports` table.
struct ImportRecord {
  std::string kind;         // "metro" | "pois" | "roads"
  std::string target_id;    // city or road network id
  std::string source;       // file name(s)
  std::string fingerprint;  // hash of the source bytes
  std::size_t rows = 0;
  double seconds = 0.0;
};

// Fingerprint of the last import of (kind, target) since the target was last deleted, if any.
std::optional<std::string> last_fingerprint(Db& db, const std::string& kind, const std::string& target_id);

// --- cities ---
struct CityMeta {
  std::string id;
  std::string name;
  std::string attribution;
};
// Creates or replaces the city's metro network (its POIs stay). Returns the new version.
std::int64_t save_city_metro(Db& db, const CityMeta& meta, const model::MetroNetwork& net, ImportRecord record);
// Replaces the city's POIs; the city must exist. Returns the new version.
std::int64_t save_city_pois(Db& db, const std::string& city_id, const std::string& attribution,
                            const std::vector<model::Poi>& pois, ImportRecord record);
std::vector<model::CityInfo> list_cities(Db& db);
std::optional<model::CityInfo> find_city(Db& db, const std::string& id);
std::optional<std::int64_t> city_version(Db& db, const std::string& id);
std::optional<model::City> load_city(Db& db, const std::string& id);
// Deletes the city with its metro network and POIs; false when there was none. Recorded in
// the `deletions` table, so re-importing the same files afterwards imports them again.
bool delete_city(Db& db, const std::string& id);

// --- road networks ---
struct RoadMeta {
  std::string id;
  std::string name;
  std::string attribution;
};
// Creates or replaces the road network and its context layers (store/context_repo.cpp).
std::int64_t save_road_network(Db& db, const RoadMeta& meta, const model::RoadNetwork& net, ImportRecord record,
                               const model::ContextLayers& context = {});
std::vector<model::RoadNetworkInfo> list_road_networks(Db& db);
std::optional<model::RoadNetworkInfo> find_road_network(Db& db, const std::string& id);
std::optional<std::int64_t> road_network_version(Db& db, const std::string& id);
std::optional<model::RoadNetwork> load_road_network(Db& db, const std::string& id);
// Deletes the road network; false when there was none. Recorded like delete_city.
bool delete_road_network(Db& db, const std::string& id);
// The network's context layers (empty for a network without any, or unknown); within the
// caller's transaction when writing (save_road_network calls it).
void save_road_context(Db& db, const std::string& network_id, const model::ContextLayers& layers);
model::ContextLayers load_road_context(Db& db, const std::string& network_id);

// --- result cache ---
struct CachedResult {
  std::string content_type;
  std::string body;
};
std::optional<CachedResult> cache_get(Db& db, const std::string& key);
void cache_put(Db& db, const std::string& key, const std::string& kind, const CachedResult& value);
std::size_t cache_purge(Db& db, const std::string& kind = "");

// Ids are url-safe slugs: [a-z0-9][a-z0-9_-]{0,63}.
bool is_valid_id(const std::string& id);

}  // namespace tourmap::store
