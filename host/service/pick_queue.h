#pragma once
// The bounded queue in front of the one pick worker. A pick is CPU-bound and uses every
// core, so requests run one at a time, in arrival order; at most `capacity` wait. A
// request that has not started within its deadline leaves the queue unrun; a running
// pick is never cut short. close() drops the waiting ones and lets the running one end.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

namespace flexsight {

class PickQueue {
 public:
  using Clock = std::chrono::steady_clock;

  enum class Outcome {
    kDone,      // the job ran (its own result says how it went)
    kFull,      // refused: `capacity` were already waiting
    kTimedOut,  // still waiting at its deadline: taken out unrun
    kClosed,    // the queue was closed before it ran
  };

  explicit PickQueue(std::size_t capacity);
  ~PickQueue();  // close() and the worker joined
  PickQueue(const PickQueue&) = delete;
  PickQueue& operator=(const PickQueue&) = delete;

  // Queues `job`, waits until it has run on the worker thread or `start_deadline` passes
  // before it starts; `waited` (when given) receives the seconds it waited to start.
  Outcome run(std::function<void()> job, Clock::time_point start_deadline, double* waited = nullptr);

  // Waiting jobs, and whether one runs now.
  std::size_t waiting() const;
  bool busy() const;

  // No more jobs: waiting ones answer kClosed, the running one finishes; returns when the
  // worker has stopped.
  void close();

 private:
  struct Task;
  void work();

  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::shared_ptr<Task>> waiting_;
  bool busy_ = false, closed_ = false;
  std::once_flag joined_;  // close() may come from the signal thread and main at once
  std::thread worker_;
};

}  // namespace flexsight
