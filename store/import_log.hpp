#pragma once
// The `imports` table: one row per import; its id versions what the import wrote.

#include "repo.hpp"

namespace tourmap::store {

// Inserts the row (inside the caller's transaction) and returns its id, the new version.
std::int64_t record_import(Db& db, const ImportRecord& record);

}  // namespace tourmap::store
