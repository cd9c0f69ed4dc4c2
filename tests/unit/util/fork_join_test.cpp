#include "util/fork_join.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <algorithm>
#include <map>
#include <stdexcept>
#include <thread>
#include <vector>

namespace tourmap::util {
namespace {

// Work shared through an atomic counter, as the contract asks: every item is done exactly once
// whichever threads join, fn(0) runs on the caller, and the results are visible after run.
TEST(ForkJoin, SharedWorkDoneOnceAndVisibleAfterRun) {
  ForkJoin pool(3);
  ASSERT_EQ(pool.threads(), 3);
  std::size_t helped = 0;
  for (int round = 0; round < 200; ++round) {
    std::vector<int> done(1000, 0);
    std::atomic<std::size_t> next{0};
    std::mutex mutex;
    std::map<int, std::thread::id> indices;  // t -> the thread that ran fn(t)
    pool.run([&](int t) {
      {
        std::lock_guard lock(mutex);
        EXPECT_TRUE(indices.emplace(t, std::this_thread::get_id()).second) << "index " << t << " twice";
      }
      for (std::size_t k; (k = next.fetch_add(1)) < done.size();) {
        ++done[k];
        std::this_thread::yield();  // long enough for the workers to join now and then
      }
    });
    ASSERT_TRUE(indices.count(0));
    EXPECT_EQ(indices[0], std::this_thread::get_id()) << "round " << round;
    for (const auto& [t, id] : indices) {
      ASSERT_TRUE(t >= 0 && t < 3);
      if (t != 0) {
        EXPECT_NE(id, std::this_thread::get_id());
      }
    }
    helped += indices.size() > 1;
    ASSERT_EQ(std::count(done.begin(), done.end(), 1), 1000) << "round " << round;
  }
  EXPECT_GT(helped, 0u);  // the workers do take part
}

TEST(ForkJoin, OneThreadRunsOnTheCaller) {
  ForkJoin pool(1);
  std::thread::id id;
  int calls = 0;
  pool.run([&](int t) {
    EXPECT_EQ(t, 0);
    ++calls;
    id = std::this_thread::get_id();
  });
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(id, std::this_thread::get_id());
}

TEST(ForkJoin, RethrowsAfterTheStartedCallsHaveEnded) {
  ForkJoin pool(2);
  std::atomic<int> running{0}, worker_threw{0};
  EXPECT_THROW(pool.run([&](int t) {
    ++running;
    if (t == 0) {
      // Give the worker a chance to join, then fail on the caller.
      for (int k = 0; k < 1000 && worker_threw == 0; ++k) std::this_thread::yield();
      --running;
      throw std::runtime_error("caller");
    }
    ++worker_threw;
    --running;
    throw std::logic_error("worker");
  }),
               std::runtime_error);  // the caller's exception wins
  EXPECT_EQ(running.load(), 0);      // nothing still running when run returned
  std::atomic<int> after{0};         // the pool is still usable
  pool.run([&](int) { ++after; });
  EXPECT_GE(after.load(), 1);
}

}  // namespace
}  // namespace tourmap::util
