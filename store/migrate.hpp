#pragma once
// Schema migrations: migrations/NNNN_name.sql, embedded into the binary at build time and
// applied in order, each in one transaction, recorded in schema_version. Safe to run twice and
// from two processes at once.

#include "sqlite.hpp"

#include <string>
#include <vector>

namespace tourmap::store {

struct Migration {
  int version;
  std::string name;
  std::string sql;
};

// The migrations compiled into this binary, in version order.
const std::vector<Migration>& embedded_migrations();

// Applies the pending ones; returns the names of those applied now.
std::vector<std::string> migrate(Db& db, const std::vector<Migration>& migrations = embedded_migrations());

// Highest applied version (0 for a new database).
int schema_version(Db& db);

}  // namespace tourmap::store
