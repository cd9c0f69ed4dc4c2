#include "api_keys.hpp"

#include <openssl/crypto.h>
#include <openssl/rand.h>
#include <openssl/sha.h>

#include <stdexcept>

namespace tourmap::store {

namespace {

constexpr std::string_view kPrefix = "tm_";
constexpr std::size_t kIdBytes = 8;       // 16 hex digits
constexpr std::size_t kSecretBytes = 32;  // 64 hex digits, 256 bits

std::string hex(const unsigned char* data, std::size_t n) {
  static constexpr char digits[] = "0123456789abcdef";
  std::string out(2 * n, '0');
  for (std::size_t i = 0; i < n; ++i) {
    out[2 * i] = digits[data[i] >> 4];
    out[2 * i + 1] = digits[data[i] & 15];
  }
  return out;
}

std::string random_hex(std::size_t bytes) {
  std::vector<unsigned char> buf(bytes);
  if (RAND_bytes(buf.data(), static_cast<int>(buf.size())) != 1)
    throw std::runtime_error("no secure random bytes available for an API key");
  return hex(buf.data(), buf.size());
}

std::string sha256_hex(std::string_view text) {
  unsigned char digest[SHA256_DIGEST_LENGTH];
  SHA256(reinterpret_cast<const unsigned char*>(text.data()), text.size(), digest);
  return hex(digest, sizeof digest);
}

bool is_lower_hex(std::string_view s) {
  for (char c : s)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

struct ParsedKey {
  std::string_view id;
  std::string_view secret;
};

std::optional<ParsedKey> parse_key(std::string_view key) {
  if (key.size() != kPrefix.size() + 2 * kIdBytes + 1 + 2 * kSecretBytes) return std::nullopt;
  if (key.substr(0, kPrefix.size()) != kPrefix || key[kPrefix.size() + 2 * kIdBytes] != '_') return std::nullopt;
  ParsedKey p{key.substr(kPrefix.size(), 2 * kIdBytes), key.substr(kPrefix.size() + 2 * kIdBytes + 1)};
  if (!is_lower_hex(p.id) || !is_lower_hex(p.secret)) return std::nullopt;
  return p;
}

}  // namespace

NewApiKey create_api_key(Db& db, const std::string& name) {
  if (name.empty() || name.size() > 200) throw std::invalid_argument("key name must have 1 to 200 characters");
  NewApiKey out;
  out.id = random_hex(kIdBytes);
  const std::string secret = random_hex(kSecretBytes);
  out.key = std::string(kPrefix) + out.id + "_" + secret;
  db.prepare("INSERT INTO api_keys (id, name, secret_hash) VALUES (?, ?, ?)")
      .bind(1, out.id)
      .bind(2, name)
      .bind(3, sha256_hex(secret))
      .run();
  return out;
}

std::vector<ApiKeyInfo> list_api_keys(Db& db) {
  auto st = db.prepare(
      "SELECT id, name, created_at, coalesce(last_used_at, ''), coalesce(revoked_at, '') FROM api_keys"
      " ORDER BY created_at, id");
  std::vector<ApiKeyInfo> out;
  while (st.step()) out.push_back({st.text(0), st.text(1), st.text(2), st.text(3), st.text(4)});
  return out;
}

bool revoke_api_key(Db& db, const std::string& id) {
  db.prepare("UPDATE api_keys SET revoked_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = ? AND revoked_at IS NULL")
      .bind(1, id)
      .run();
  return db.changes() > 0;
}

std::optional<std::string> verify_api_key(Db& db, std::string_view key) {
  auto parsed = parse_key(key);
  if (!parsed) return std::nullopt;
  auto st = db.prepare("SELECT secret_hash FROM api_keys WHERE id = ? AND revoked_at IS NULL");
  st.bind(1, parsed->id);
  const bool found = st.step();
  // An unknown id still costs one hash and one comparison, so timing says nothing about ids.
  const std::string stored = found ? st.text(0) : std::string(2 * SHA256_DIGEST_LENGTH, '0');
  st.reset();
  const std::string presented = sha256_hex(parsed->secret);
  const bool equal = stored.size() == presented.size() &&
                     CRYPTO_memcmp(stored.data(), presented.data(), presented.size()) == 0;
  if (!found || !equal) return std::nullopt;
  std::string id(parsed->id);
  db.prepare("UPDATE api_keys SET last_used_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = ?").bind(1, id).run();
  return id;
}

}  // namespace tourmap::store
