-- tourmap store, version 2: API keys for the write endpoints (imports, deletes, cache purge).
-- A key is shown once when created ("tm_<id>_<secret>"); the store keeps only the SHA-256 of its
-- secret, so a copy of the database does not give anyone write access.
CREATE TABLE api_keys (
  id           TEXT PRIMARY KEY,       -- public part of the key, 16 hex digits
  name         TEXT NOT NULL,          -- who or what the key is for
  secret_hash  TEXT NOT NULL,          -- SHA-256 of the secret part, hex
  created_at   TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  last_used_at TEXT,
  revoked_at   TEXT                    -- set by `tourmap keys revoke`; a revoked key never verifies
);
