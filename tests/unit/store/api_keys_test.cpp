// API keys: created keys verify, anything else (malformed, unknown id, wrong secret, revoked)
// does not, and the store never holds the key itself.

#include "store/api_keys.hpp"
#include "store/migrate.hpp"
#include "temp_dir.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace tourmap::store {
namespace {

class ApiKeysTest : public ::testing::Test {
 protected:
  ApiKeysTest() : db(dir.file("t.db")) { migrate(db); }
  test::TempDir dir;
  Db db;
};

TEST_F(ApiKeysTest, CreatedKeyVerifies) {
  auto key = create_api_key(db, "importer bot");
  EXPECT_EQ(key.id.size(), 16u);
  EXPECT_EQ(key.key.size(), 3u + 16u + 1u + 64u);
  EXPECT_EQ(key.key.substr(0, 3 + 16), "tm_" + key.id);
  EXPECT_EQ(verify_api_key(db, key.key), key.id);
  auto listed = list_api_keys(db);
  ASSERT_EQ(listed.size(), 1u);
  EXPECT_EQ(listed[0].name, "importer bot");
  EXPECT_FALSE(listed[0].last_used_at.empty());  // the verification above was recorded
  EXPECT_TRUE(listed[0].revoked_at.empty());
}

TEST_F(ApiKeysTest, StoreHoldsOnlyAHashOfTheSecret) {
  auto key = create_api_key(db, "ops");
  const std::string secret = key.key.substr(3 + 16 + 1);
  auto st = db.prepare("SELECT id, name, secret_hash FROM api_keys");
  ASSERT_TRUE(st.step());
  for (int col = 0; col < 3; ++col) EXPECT_EQ(st.text(col).find(secret), std::string::npos) << col;
  EXPECT_EQ(st.text(2).size(), 64u);
}

TEST_F(ApiKeysTest, KeysAreDistinct) {
  auto a = create_api_key(db, "a");
  auto b = create_api_key(db, "b");
  EXPECT_NE(a.id, b.id);
  EXPECT_NE(a.key, b.key);
  EXPECT_EQ(verify_api_key(db, a.key), a.id);
  EXPECT_EQ(verify_api_key(db, b.key), b.id);
}

TEST_F(ApiKeysTest, WrongOrMalformedKeysDoNotVerify) {
  auto key = create_api_key(db, "ops");
  std::string wrong_secret = key.key;
  wrong_secret.back() = wrong_secret.back() == '0' ? '1' : '0';
  EXPECT_FALSE(verify_api_key(db, wrong_secret));
  std::string other_id = key.key;
  other_id[3] = other_id[3] == 'a' ? 'b' : 'a';
  EXPECT_FALSE(verify_api_key(db, other_id));
  EXPECT_FALSE(verify_api_key(db, ""));
  EXPECT_FALSE(verify_api_key(db, key.key.substr(0, key.key.size() - 1)));  // short
  EXPECT_FALSE(verify_api_key(db, key.key + "0"));                         // long
  std::string upper = key.key;
  for (auto& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  EXPECT_FALSE(verify_api_key(db, upper));
  std::string injected = key.key;
  injected.replace(3, 16, "' OR 1=1 --     ");
  EXPECT_FALSE(verify_api_key(db, injected));
}

TEST_F(ApiKeysTest, RevokedKeyStopsVerifying) {
  auto key = create_api_key(db, "ops");
  EXPECT_TRUE(revoke_api_key(db, key.id));
  EXPECT_FALSE(verify_api_key(db, key.key));
  EXPECT_FALSE(revoke_api_key(db, key.id));  // already revoked
  EXPECT_FALSE(revoke_api_key(db, "0000000000000000"));
  EXPECT_FALSE(list_api_keys(db)[0].revoked_at.empty());
}

TEST_F(ApiKeysTest, NameIsRequired) {
  EXPECT_THROW(create_api_key(db, ""), std::invalid_argument);
  EXPECT_THROW(create_api_key(db, std::string(201, 'x')), std::invalid_argument);
  EXPECT_TRUE(list_api_keys(db).empty());
}

}  // namespace
}  // namespace tourmap::store
