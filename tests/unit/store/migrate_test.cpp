#include "store/migrate.hpp"
#include "temp_dir.hpp"

#include <gtest/gtest.h>

namespace tourmap::store {
namespace {

TEST(Migrate, AppliesOnceAndIsSafeToRepeat) {
  test::TempDir dir;
  Db db(dir.file("t.db"));
  EXPECT_EQ(schema_version(db), 0);
  auto first = migrate(db);
  EXPECT_EQ(first.size(), embedded_migrations().size());
  EXPECT_EQ(schema_version(db), embedded_migrations().back().version);
  EXPECT_TRUE(migrate(db).empty());
  // A second connection (another process) sees the same schema and applies nothing.
  Db other(dir.file("t.db"));
  EXPECT_TRUE(migrate(other).empty());
}

TEST(Migrate, EmbeddedMigrationsAreOrderedAndNamed) {
  const auto& all = embedded_migrations();
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.front().name, "0001_init");
  for (std::size_t i = 1; i < all.size(); ++i) EXPECT_LT(all[i - 1].version, all[i].version);
}

TEST(Migrate, FailingMigrationRollsBackEntirely) {
  test::TempDir dir;
  Db db(dir.file("t.db"));
  std::vector<Migration> broken = {{1, "0001_ok", "CREATE TABLE a (x INTEGER);"},
                                   {2, "0002_bad", "CREATE TABLE b (x INTEGER); INSERT INTO nope VALUES (1);"}};
  EXPECT_THROW(migrate(db, broken), DbError);
  EXPECT_EQ(schema_version(db), 1);
  // Table b from the failed migration must not exist.
  auto st = db.prepare("SELECT COUNT(*) FROM sqlite_master WHERE name = 'b'");
  st.step();
  EXPECT_EQ(st.int64(0), 0);
}

TEST(Db, UsesWalAndForeignKeys) {
  test::TempDir dir;
  Db db(dir.file("t.db"));
  auto mode = db.prepare("PRAGMA journal_mode");
  mode.step();
  EXPECT_EQ(mode.text(0), "wal");
  auto fk = db.prepare("PRAGMA foreign_keys");
  fk.step();
  EXPECT_EQ(fk.int64(0), 1);
}

}  // namespace
}  // namespace tourmap::store
