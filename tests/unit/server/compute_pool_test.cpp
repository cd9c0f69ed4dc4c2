#include "server/compute_pool.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <future>

namespace tourmap::server {
namespace {

using namespace std::chrono_literals;

TEST(ComputePool, RunsTasksOffTheCallingThread) {
  ComputePool pool(2, 8);
  std::promise<std::thread::id> ran;
  ASSERT_TRUE(pool.submit([&](bool) { ran.set_value(std::this_thread::get_id()); }, ComputePool::Clock::now() + 1s));
  EXPECT_NE(ran.get_future().get(), std::this_thread::get_id());
}

TEST(ComputePool, BoundedQueueRefuses) {
  ComputePool pool(1, 2);
  std::promise<void> release;
  auto gate = release.get_future().share();
  std::promise<void> started;
  auto far = ComputePool::Clock::now() + 10s;
  ASSERT_TRUE(pool.submit([&](bool) { started.set_value(); gate.wait(); }, far));
  started.get_future().wait();  // the worker is busy
  EXPECT_TRUE(pool.submit([](bool) {}, far));
  EXPECT_TRUE(pool.submit([](bool) {}, far));
  EXPECT_FALSE(pool.submit([](bool) {}, far));  // queue full
  EXPECT_EQ(pool.queued(), 2u);
  release.set_value();
  pool.shutdown();
  EXPECT_EQ(pool.queued(), 0u);
}

TEST(ComputePool, ExpiredTasksAreToldSo) {
  ComputePool pool(1, 4);
  std::promise<bool> expired;
  ASSERT_TRUE(pool.submit([&](bool e) { expired.set_value(e); }, ComputePool::Clock::now() - 1ms));
  EXPECT_TRUE(expired.get_future().get());
}

TEST(ComputePool, ShutdownDrainsQueuedWork) {
  std::atomic<int> done{0};
  {
    ComputePool pool(1, 100);
    for (int i = 0; i < 50; ++i) pool.submit([&](bool) { ++done; }, ComputePool::Clock::now() + 10s);
    pool.shutdown();
    EXPECT_FALSE(pool.submit([&](bool) { ++done; }, ComputePool::Clock::now() + 10s));
  }
  EXPECT_EQ(done, 50);
}

}  // namespace
}  // namespace tourmap::server
