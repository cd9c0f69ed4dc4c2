-- tourmap store, version 3: deletions of cities and road networks. An import whose source has
-- the fingerprint of the target's last import is skipped as unchanged; after the target was
-- deleted that import no longer describes anything stored, so a deletion makes every import of
-- its target up to it stale and the same bytes import again (store/import_log.cpp).
CREATE TABLE deletions (
  id             INTEGER PRIMARY KEY AUTOINCREMENT,
  kind           TEXT NOT NULL CHECK (kind IN ('city', 'roads')),  -- a city: its metro and POI imports
  target_id      TEXT NOT NULL,          -- city id or road network id
  last_import_id INTEGER NOT NULL,       -- MAX(imports.id) at the deletion: imports up to it are stale
  deleted_at     TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
CREATE INDEX deletions_target ON deletions (kind, target_id);
