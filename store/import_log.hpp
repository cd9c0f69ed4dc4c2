#pragma once
// The `imports` table: one row per import; its id versions what the import wrote. The
// `deletions` table: one row per deleted city or road network, which makes the imports of the
// target before it stale (last_fingerprint ignores them).

#include "repo.hpp"

namespace tourmap::store {

// Inserts the row (inside the caller's transaction) and returns its id, the new version.
std::int64_t record_import(Db& db, const ImportRecord& record);

// Records (inside the caller's transaction) that the city ("city": its metro and POI imports)
// or road network ("roads") `target_id` was deleted.
void record_deletion(Db& db, const std::string& kind, const std::string& target_id);

}  // namespace tourmap::store
