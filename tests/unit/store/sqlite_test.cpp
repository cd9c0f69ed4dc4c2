#include "store/sqlite.hpp"
#include "temp_dir.hpp"

#include <gtest/gtest.h>

namespace tourmap::store {
namespace {

TEST(Sqlite, CachedStatementIsPreparedOnceAndRebound) {
  test::TempDir dir;
  Db db(dir.file("t.db"));
  db.exec("CREATE TABLE t (k TEXT PRIMARY KEY, v INTEGER)");
  db.exec("INSERT INTO t VALUES ('a', 1), ('b', 2)");
  const char* sql = "SELECT v FROM t WHERE k = ?";
  const Stmt* first = nullptr;
  {
    auto st = db.cached(sql);
    first = &*st;
    st->bind(1, "a");
    ASSERT_TRUE(st->step());
    EXPECT_EQ(st->int64(0), 1);
  }
  auto st = db.cached(sql);
  EXPECT_EQ(&*st, first);
  st->bind(1, "b");
  ASSERT_TRUE(st->step());
  EXPECT_EQ(st->int64(0), 2);
}

// A handle left after one row (the statement not run to its end) must not keep the connection's
// read snapshot: a commit from another connection is seen by the next read.
TEST(Sqlite, CachedStatementReleasesItsSnapshot) {
  test::TempDir dir;
  Db reader(dir.file("t.db"));
  reader.exec("CREATE TABLE t (k TEXT PRIMARY KEY, v INTEGER)");
  reader.exec("INSERT INTO t VALUES ('a', 1), ('b', 2)");
  auto read_a = [&] {
    auto st = reader.cached("SELECT v FROM t WHERE k >= ? ORDER BY k");  // two rows, one stepped
    st->bind(1, "a");
    EXPECT_TRUE(st->step());
    return st->int64(0);
  };
  EXPECT_EQ(read_a(), 1);
  Db writer(dir.file("t.db"));
  writer.exec("UPDATE t SET v = 10 WHERE k = 'a'");
  EXPECT_EQ(read_a(), 10);
}

// A transaction inside another is a savepoint: its rollback undoes only its own writes, its
// commit holds only if the outer one commits.
TEST(Sqlite, NestedTransactionIsASavepoint) {
  test::TempDir dir;
  Db db(dir.file("t.db"));
  db.exec("CREATE TABLE t (v INTEGER)");
  auto count = [&] {
    auto st = db.prepare("SELECT COUNT(*) FROM t");
    EXPECT_TRUE(st.step());
    return st.int64(0);
  };
  {
    Transaction outer(db);
    db.exec("INSERT INTO t VALUES (1)");
    {
      Transaction inner(db);
      db.exec("INSERT INTO t VALUES (2)");
    }  // rolled back to the savepoint
    EXPECT_EQ(count(), 1);
    {
      Transaction inner(db);
      db.exec("INSERT INTO t VALUES (3)");
      inner.commit();
    }
    EXPECT_TRUE(db.in_transaction());
    EXPECT_EQ(count(), 2);
  }  // the outer one rolls everything back
  EXPECT_FALSE(db.in_transaction());
  EXPECT_EQ(count(), 0);
  {
    Transaction outer(db);
    Transaction inner(db);
    db.exec("INSERT INTO t VALUES (4)");
    inner.commit();
    outer.commit();
  }
  EXPECT_EQ(count(), 1);
}

}  // namespace
}  // namespace tourmap::store
