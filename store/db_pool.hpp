#pragma once
// SQLite connections for the server's threads: each borrower gets its own connection (SQLite
// connections are not shared across threads here), returned to the pool afterwards.

#include "sqlite.hpp"

#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace tourmap::store {

class DbPool {
 public:
  explicit DbPool(std::string path) : path_(std::move(path)) {}

  class Lease {
   public:
    Lease(DbPool& pool, std::unique_ptr<Db> db) : pool_(&pool), db_(std::move(db)) {}
    Lease(Lease&&) = default;
    ~Lease() {
      if (db_) pool_->give_back(std::move(db_));
    }
    Db& operator*() { return *db_; }
    Db* operator->() { return db_.get(); }

   private:
    DbPool* pool_;
    std::unique_ptr<Db> db_;
  };

  Lease acquire() {
    {
      std::lock_guard lock(mutex_);
      if (!idle_.empty()) {
        auto db = std::move(idle_.back());
        idle_.pop_back();
        return Lease(*this, std::move(db));
      }
    }
    return Lease(*this, std::make_unique<Db>(path_));
  }

  const std::string& path() const { return path_; }

  // Closes idle connections (at shutdown: leaves the WAL checkpointed by the last close).
  void close_idle() {
    std::lock_guard lock(mutex_);
    idle_.clear();
  }

 private:
  void give_back(std::unique_ptr<Db> db) {
    std::lock_guard lock(mutex_);
    idle_.push_back(std::move(db));
  }

  std::string path_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<Db>> idle_;
};

}  // namespace tourmap::store
