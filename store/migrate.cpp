#include "migrate.hpp"

namespace tourmap::store {
namespace {

void ensure_version_table(Db& db) {
  db.exec(
      "CREATE TABLE IF NOT EXISTS schema_version ("
      " version INTEGER PRIMARY KEY, name TEXT NOT NULL,"
      " applied_at TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')))");
}

}  // namespace

int schema_version(Db& db) {
  ensure_version_table(db);
  auto st = db.prepare("SELECT COALESCE(MAX(version), 0) FROM schema_version");
  st.step();
  return static_cast<int>(st.int64(0));
}

std::vector<std::string> migrate(Db& db, const std::vector<Migration>& migrations) {
  ensure_version_table(db);
  std::vector<std::string> applied;
  for (const auto& m : migrations) {
    Transaction tx(db);
    // Re-read inside the write transaction: another process may have just applied it.
    auto st = db.prepare("SELECT 1 FROM schema_version WHERE version = ?");
    st.bind(1, m.version);
    if (st.step()) continue;
    try {
      db.exec(m.sql);
    } catch (const DbError& e) {
      throw DbError("migration " + m.name + " failed: " + e.what());
    }
    db.prepare("INSERT INTO schema_version (version, name) VALUES (?, ?)").bind(1, m.version).bind(2, m.name).run();
    tx.commit();
    applied.push_back(m.name);
  }
  return applied;
}

}  // namespace tourmap::store
