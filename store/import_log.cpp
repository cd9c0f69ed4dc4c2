#include "import_log.hpp"

namespace tourmap::store {

std::optional<std::string> last_fingerprint(Db& db, const std::string& kind, const std::string& target_id) {
  // Imports up to the target's last deletion describe nothing stored any more.
  auto st = db.prepare(
      "SELECT fingerprint FROM imports WHERE kind = ? AND target_id = ? AND id > COALESCE("
      "(SELECT MAX(last_import_id) FROM deletions WHERE kind = ? AND target_id = ?), 0)"
      " ORDER BY id DESC LIMIT 1");
  st.bind(1, kind).bind(2, target_id).bind(3, kind == "roads" ? "roads" : "city").bind(4, target_id);
  if (!st.step()) return std::nullopt;
  return st.text(0);
}

void record_deletion(Db& db, const std::string& kind, const std::string& target_id) {
  db.prepare("INSERT INTO deletions (kind, target_id, last_import_id)"
             " VALUES (?, ?, (SELECT COALESCE(MAX(id), 0) FROM imports))")
      .bind(1, kind)
      .bind(2, target_id)
      .run();
}

std::int64_t record_import(Db& db, const ImportRecord& record) {
  db.prepare("INSERT INTO imports (kind, target_id, source, fingerprint, rows, seconds) VALUES (?, ?, ?, ?, ?, ?)")
      .bind(1, record.kind)
      .bind(2, record.target_id)
      .bind(3, record.source)
      .bind(4, record.fingerprint)
      .bind(5, record.rows)
      .bind(6, record.seconds)
      .run();
  return db.last_insert_rowid();
}

bool is_valid_id(const std::string& id) {
  if (id.empty() || id.size() > 64) return false;
  for (std::size_t i = 0; i < id.size(); ++i) {
    char c = id[i];
    bool ok = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || (i > 0 && (c == '-' || c == '_'));
    if (!ok) return false;
  }
  return true;
}

}  // namespace tourmap::store
