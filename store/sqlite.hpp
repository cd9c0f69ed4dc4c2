#pragma once
// A thin RAII layer over the SQLite C API: connections, prepared statements, transactions.
// Written here because the C API is the well-kept library; this only adds ownership and errors.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace tourmap::store {

class DbError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Stmt {
 public:
  Stmt(sqlite3* db, std::string_view sql);
  ~Stmt();
  Stmt(Stmt&& other) noexcept;
  Stmt& operator=(Stmt&&) = delete;
  Stmt(const Stmt&) = delete;

  // Parameters are 1-based as in SQLite.
  Stmt& bind(int i, std::int64_t v);
  Stmt& bind(int i, int v) { return bind(i, static_cast<std::int64_t>(v)); }
  Stmt& bind(int i, std::size_t v) { return bind(i, static_cast<std::int64_t>(v)); }
  Stmt& bind(int i, double v);
  Stmt& bind(int i, std::string_view v);
  Stmt& bind(int i, const char* v) { return bind(i, std::string_view(v)); }
  Stmt& bind(int i, const std::string& v) { return bind(i, std::string_view(v)); }
  Stmt& bind(int i, std::optional<double> v);
  Stmt& bind_blob(int i, const void* data, std::size_t size);
  Stmt& bind_null(int i);

  // Runs one step: true while a row is available.
  bool step();
  // Runs to completion (for statements without results).
  void run();
  void reset();

  // Columns are 0-based as in SQLite.
  std::int64_t int64(int col) const;
  double real(int col) const;
  std::string text(int col) const;
  std::optional<double> opt_real(int col) const;
  bool is_null(int col) const;
  std::vector<unsigned char> blob(int col) const;

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_;
};

// A statement its connection keeps prepared (Db::cached). The handle resets it and clears its
// bindings when it goes, so the statement never stays mid-step holding the connection's read
// snapshot (later reads on the connection would see old data).
class CachedStmt {
 public:
  explicit CachedStmt(Stmt& stmt) : stmt_(&stmt) {}
  ~CachedStmt() { stmt_->reset(); }
  CachedStmt(const CachedStmt&) = delete;
  CachedStmt& operator=(const CachedStmt&) = delete;
  Stmt& operator*() const { return *stmt_; }
  Stmt* operator->() const { return stmt_; }

 private:
  Stmt* stmt_;
};

class Db {
 public:
  // Opens (creating if needed) the database at `path` with WAL, foreign keys and a busy timeout.
  explicit Db(const std::string& path, bool read_only = false);
  ~Db();
  Db(const Db&) = delete;
  Db& operator=(const Db&) = delete;

  void exec(std::string_view sql);
  Stmt prepare(std::string_view sql) { return Stmt(db_, sql); }
  // Prepared on first use and kept by this connection: for the queries on every request's path,
  // where preparing costs more than running them. One handle per statement at a time.
  CachedStmt cached(std::string_view sql);
  std::int64_t last_insert_rowid() const;
  // Rows changed by the last INSERT/UPDATE/DELETE.
  std::int64_t changes() const;
  const std::string& path() const { return path_; }
  sqlite3* handle() { return db_; }
  // True inside BEGIN ... COMMIT/ROLLBACK.
  bool in_transaction() const;

 private:
  sqlite3* db_ = nullptr;
  std::string path_;
  std::map<std::string, Stmt, std::less<>> cached_;  // finalized before the connection closes
};

// BEGIN IMMEDIATE on construction; ROLLBACK on destruction unless commit() ran. Inside another
// transaction of the same connection it is a SAVEPOINT instead (released by commit(), rolled
// back to on destruction), so writes that each run in a transaction can be composed into one
// (store/city_source.cpp writes a city's transit, POIs and roads together).
class Transaction {
 public:
  explicit Transaction(Db& db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  Db& db_;
  bool done_ = false;
  bool nested_ = false;
};

// BEGIN (deferred) for a consistent multi-statement read; COMMIT on destruction.
class ReadTransaction {
 public:
  explicit ReadTransaction(Db& db) : db_(db) { db_.exec("BEGIN"); }
  ~ReadTransaction();
  ReadTransaction(const ReadTransaction&) = delete;
  ReadTransaction& operator=(const ReadTransaction&) = delete;

 private:
  Db& db_;
};

}  // namespace tourmap::store
