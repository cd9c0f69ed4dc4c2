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

}  // namespace
}  // namespace tourmap::store
