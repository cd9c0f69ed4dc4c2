#pragma once
// API keys for the write endpoints. A key reads "tm_<id>_<secret>": the id (16 hex digits) finds
// the row, the secret (64 hex digits, 256 random bits) proves possession. Only SHA-256(secret)
// is stored. Because the secret is random and long, a plain hash is enough (no salt or slow KDF:
// those defend low-entropy passwords); the comparison runs in constant time.

#include "sqlite.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tourmap::store {

struct NewApiKey {
  std::string id;
  std::string key;  // the full key, shown once, never stored
};

struct ApiKeyInfo {
  std::string id;
  std::string name;
  std::string created_at;
  std::string last_used_at;  // empty: never used
  std::string revoked_at;    // empty: active
};

// Creates a key named `name` (1..200 characters); throws std::invalid_argument otherwise.
NewApiKey create_api_key(Db& db, const std::string& name);
std::vector<ApiKeyInfo> list_api_keys(Db& db);
// Marks the key revoked; false when there is no active key with that id.
bool revoke_api_key(Db& db, const std::string& id);
// The id of the active key `key` is, or nullopt (malformed, unknown, revoked or wrong secret).
// Records the use when it verifies.
std::optional<std::string> verify_api_key(Db& db, std::string_view key);

}  // namespace tourmap::store
