#include "repo.hpp"

namespace tourmap::store {

std::optional<CachedResult> cache_get(Db& db, const std::string& key) {
  CachedResult out;
  {
    auto st = db.cached("SELECT content_type, body FROM result_cache WHERE key = ?");
    st->bind(1, key);
    if (!st->step()) return std::nullopt;
    auto blob = st->blob(1);
    out = CachedResult{st->text(0), std::string(blob.begin(), blob.end())};
  }
  db.cached("UPDATE result_cache SET hits = hits + 1, last_used = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE key = ?")
      ->bind(1, key)
      .run();
  return out;
}

void cache_put(Db& db, const std::string& key, const std::string& kind, const CachedResult& value) {
  db.prepare(
        "INSERT INTO result_cache (key, kind, content_type, body) VALUES (?, ?, ?, ?)"
        " ON CONFLICT (key) DO UPDATE SET content_type = excluded.content_type, body = excluded.body,"
        " last_used = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')")
      .bind(1, key)
      .bind(2, kind)
      .bind(3, value.content_type)
      .bind_blob(4, value.body.data(), value.body.size())
      .run();
}

std::size_t cache_purge(Db& db, const std::string& kind) {
  auto st = kind.empty() ? db.prepare("DELETE FROM result_cache")
                         : db.prepare("DELETE FROM result_cache WHERE kind = ?");
  if (!kind.empty()) st.bind(1, kind);
  st.run();
  return static_cast<std::size_t>(db.changes());
}

}  // namespace tourmap::store
