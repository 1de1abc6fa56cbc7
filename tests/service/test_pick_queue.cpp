// The queue in front of the one pick worker (host/service/pick_queue.h): jobs run one at a
// time in arrival order, one more than the capacity is refused, a job not started by its
// deadline leaves unrun, and close() drops the waiting ones while the running one ends.
#include "host/service/pick_queue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <vector>

namespace flexsight {
namespace {

using namespace std::chrono_literals;
using Outcome = PickQueue::Outcome;

PickQueue::Clock::time_point in(std::chrono::milliseconds ms) { return PickQueue::Clock::now() + ms; }

// Waits until `queue` holds `n` waiting jobs.
void await_waiting(const PickQueue& queue, std::size_t n) {
  while (queue.waiting() != n) std::this_thread::sleep_for(1ms);
}

TEST(PickQueue, RunsJobsOneAtATimeAndRefusesBeyondItsCapacity) {
  PickQueue queue(2);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<int> running{0}, most{0};
  std::vector<int> order;
  std::mutex order_mutex;
  auto job = [&](int id) {
    return [&, id] {
      most = std::max(most.load(), ++running);
      released.wait();
      std::lock_guard<std::mutex> lock(order_mutex);
      order.push_back(id);
      --running;
    };
  };
  auto first = std::async(std::launch::async, [&] { return queue.run(job(1), in(10s)); });
  while (!queue.busy()) std::this_thread::sleep_for(1ms);
  auto second = std::async(std::launch::async, [&] { return queue.run(job(2), in(10s)); });
  await_waiting(queue, 1);
  auto third = std::async(std::launch::async, [&] { return queue.run(job(3), in(10s)); });
  await_waiting(queue, 2);
  EXPECT_EQ(queue.run(job(4), in(10s)), Outcome::kFull);
  release.set_value();
  EXPECT_EQ(first.get(), Outcome::kDone);
  EXPECT_EQ(second.get(), Outcome::kDone);
  EXPECT_EQ(third.get(), Outcome::kDone);
  EXPECT_EQ(order, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(most.load(), 1);
}

TEST(PickQueue, AJobNotStartedByItsDeadlineLeavesUnrun) {
  PickQueue queue(4);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  auto busy = std::async(std::launch::async, [&] { return queue.run([&] { released.wait(); }, in(10s)); });
  while (!queue.busy()) std::this_thread::sleep_for(1ms);
  bool ran = false;
  double waited = 0.0;
  EXPECT_EQ(queue.run([&] { ran = true; }, in(50ms), &waited), Outcome::kTimedOut);
  EXPECT_GE(waited, 0.04);
  EXPECT_EQ(queue.waiting(), 0u);
  release.set_value();
  EXPECT_EQ(busy.get(), Outcome::kDone);
  EXPECT_FALSE(ran);
  EXPECT_EQ(queue.run([&] { ran = true; }, in(10s)), Outcome::kDone) << "the queue still serves";
  EXPECT_TRUE(ran);
}

TEST(PickQueue, CloseDropsTheWaitingAndFinishesTheRunning) {
  PickQueue queue(4);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  bool finished = false, ran = false;
  auto running = std::async(std::launch::async, [&] {
    return queue.run([&] { released.wait(); finished = true; }, in(10s));
  });
  while (!queue.busy()) std::this_thread::sleep_for(1ms);
  auto waiting = std::async(std::launch::async, [&] { return queue.run([&] { ran = true; }, in(10s)); });
  await_waiting(queue, 1);
  auto closing = std::async(std::launch::async, [&] { queue.close(); });
  EXPECT_EQ(waiting.get(), Outcome::kClosed);
  release.set_value();
  closing.get();
  EXPECT_EQ(running.get(), Outcome::kDone);
  EXPECT_TRUE(finished);
  EXPECT_FALSE(ran);
  EXPECT_EQ(queue.run([] {}, in(10s)), Outcome::kClosed);
}

}  // namespace
}  // namespace flexsight
