#include "api/layout_improver.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <thread>

namespace tourmap::api {
namespace {

using namespace std::chrono_literals;

// Waits (bounded) until `ready` holds.
template <typename F>
bool eventually(F ready) {
  for (int i = 0; i < 500; ++i) {
    if (ready()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return ready();
}

// A job that runs until the improver stops it.
LayoutImprover::Job until_stopped(std::atomic<bool>& started) {
  return [&started](const std::atomic<bool>& stop) {
    started = true;
    while (!stop) std::this_thread::sleep_for(1ms);
  };
}

TEST(LayoutImprover, QueueIsBoundedDeduplicatedAndDropsTheOldest) {
  LayoutImprover improver(8);
  std::atomic<bool> started{false};
  ASSERT_EQ(improver.push("running", until_stopped(started)), LayoutImprover::Admission::queued);
  ASSERT_TRUE(eventually([&] { return started.load(); }));
  EXPECT_EQ(improver.push("running", [](const std::atomic<bool>&) {}), LayoutImprover::Admission::pending);
  std::atomic<int> ran{0};
  for (int i = 0; i < 20; ++i)
    EXPECT_EQ(improver.push(std::string("key").append(std::to_string(i)), [&ran](const std::atomic<bool>&) { ++ran; }),
              LayoutImprover::Admission::queued);
  EXPECT_EQ(improver.push("key19", [](const std::atomic<bool>&) {}), LayoutImprover::Admission::pending);
  auto stats = improver.stats();
  EXPECT_EQ(stats.running, 1u);
  EXPECT_EQ(stats.queued, 8u) << "a client asking for many layouts queues at most 8 improvements";
  EXPECT_EQ(stats.dropped, 12u);
  improver.stop();  // stops the running job, drops the waiting ones
  EXPECT_EQ(ran.load(), 0);
  EXPECT_EQ(improver.stats().queued, 0u);
  EXPECT_EQ(improver.push("later", [](const std::atomic<bool>&) {}), LayoutImprover::Admission::refused);
}

TEST(LayoutImprover, AJobThatThrowsIsCountedAndTheQueueGoesOn) {
  LayoutImprover improver(4);
  improver.push("throws", [](const std::atomic<bool>&) { throw std::runtime_error("boom"); });
  std::atomic<bool> next_ran{false};
  improver.push("next", [&next_ran](const std::atomic<bool>&) { next_ran = true; });
  EXPECT_TRUE(eventually([&] { return next_ran.load(); }));
  EXPECT_TRUE(eventually([&] { return improver.stats().failed == 1; }));
  improver.stop();
}

}  // namespace
}  // namespace tourmap::api
