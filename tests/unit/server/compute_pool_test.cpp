#include "server/compute_pool.hpp"

#include "slowdown.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <future>
#include <mutex>
#include <string>
#include <vector>

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

// A queued task whose deadline passes is answered then, not when a worker frees up: the
// watcher expires it while the only worker is still busy.
TEST(ComputePool, QueuedTasksExpireWhileEveryWorkerIsBusy) {
  ComputePool pool(1, 8);
  std::promise<void> release;
  auto gate = release.get_future().share();
  std::promise<void> started;
  ASSERT_TRUE(pool.submit([&](bool) { started.set_value(); gate.wait(); }, ComputePool::Clock::now() + 10s));
  started.get_future().wait();
  std::promise<ComputePool::Clock::time_point> expired_at;
  const auto submitted = ComputePool::Clock::now();
  ASSERT_TRUE(pool.submit(
      [&](bool expired) {
        if (expired) expired_at.set_value(ComputePool::Clock::now());
      },
      submitted + 100ms));
  auto f = expired_at.get_future();
  ASSERT_EQ(f.wait_for(2s), std::future_status::ready) << "the queued task was not expired while the worker was busy";
  const auto waited = f.get() - submitted;
  EXPECT_GE(waited, 100ms);
  EXPECT_LT(waited, 600ms * static_cast<int>(test::kSlowdown));
  EXPECT_EQ(pool.queued(), 0u);
  EXPECT_EQ(pool.expired_in_queue(), 1u);
  release.set_value();
  pool.shutdown();  // before the gate the worker waits on goes out of scope
}

TEST(ComputePool, CapsTasksPerClient) {
  ComputePool pool({1, 16, 2});
  std::promise<void> release;
  auto gate = release.get_future().share();
  auto far = ComputePool::Clock::now() + 10s;
  std::atomic<int> ran{0};
  auto blocking = [&](bool) {
    ++ran;
    gate.wait();
  };
  EXPECT_EQ(pool.admit(blocking, far, "a"), ComputePool::Admission::accepted);  // running
  EXPECT_EQ(pool.admit(blocking, far, "a"), ComputePool::Admission::accepted);  // queued
  EXPECT_EQ(pool.admit(blocking, far, "a"), ComputePool::Admission::client_busy);
  EXPECT_EQ(pool.admit(blocking, far, "b"), ComputePool::Admission::accepted);  // another client is not capped
  EXPECT_EQ(pool.clients(), 2u);
  release.set_value();
  pool.shutdown();
  EXPECT_EQ(ran, 3);
  EXPECT_EQ(pool.clients(), 0u);  // idle clients are forgotten
}

// Round-robin across clients: a client's single task runs before the rest of another's burst.
TEST(ComputePool, ServesClientsInTurn) {
  ComputePool pool(1, 64);
  std::promise<void> release;
  auto gate = release.get_future().share();
  std::promise<void> started;
  auto far = ComputePool::Clock::now() + 10s;
  ASSERT_TRUE(pool.submit([&](bool) { started.set_value(); gate.wait(); }, far, "burst"));
  started.get_future().wait();
  std::mutex m;
  std::vector<std::string> order;
  auto record = [&](std::string who) {
    return [&, who](bool) {
      std::lock_guard lock(m);
      order.push_back(who);
    };
  };
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(pool.submit(record("burst"), far, "burst"));
  ASSERT_TRUE(pool.submit(record("single"), far, "single"));
  release.set_value();
  pool.shutdown();
  ASSERT_EQ(order.size(), 6u);
  const auto single = std::find(order.begin(), order.end(), "single") - order.begin();
  EXPECT_LE(single, 1) << "the single request waited behind the whole burst";
}

}  // namespace
}  // namespace tourmap::server
