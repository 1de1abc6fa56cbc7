#include "host/service/pick_queue.h"

#include <algorithm>

namespace flexsight {

struct PickQueue::Task {
  std::function<void()> job;
  Clock::time_point queued_at;
  enum class State { kWaiting, kRunning, kDone, kDropped } state = State::kWaiting;
  double waited = 0.0;
};

PickQueue::PickQueue(std::size_t capacity) : capacity_(capacity), worker_([this] { work(); }) {}

PickQueue::~PickQueue() { close(); }

PickQueue::Outcome PickQueue::run(std::function<void()> job, Clock::time_point start_deadline, double* waited) {
  auto task = std::make_shared<Task>();
  task->job = std::move(job);
  task->queued_at = Clock::now();
  std::unique_lock<std::mutex> lock(mutex_);
  if (closed_) return Outcome::kClosed;
  if (waiting_.size() >= capacity_) return Outcome::kFull;
  waiting_.push_back(task);
  changed_.notify_all();
  const bool started = changed_.wait_until(lock, start_deadline, [&] { return task->state != Task::State::kWaiting; });
  if (!started) {
    waiting_.erase(std::find(waiting_.begin(), waiting_.end(), task));
    if (waited) *waited = std::chrono::duration<double>(Clock::now() - task->queued_at).count();
    return Outcome::kTimedOut;
  }
  changed_.wait(lock, [&] { return task->state == Task::State::kDone || task->state == Task::State::kDropped; });
  if (waited) *waited = task->waited;
  return task->state == Task::State::kDone ? Outcome::kDone : Outcome::kClosed;
}

std::size_t PickQueue::waiting() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return waiting_.size();
}

bool PickQueue::busy() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return busy_;
}

void PickQueue::close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
    for (const auto& task : waiting_) task->state = Task::State::kDropped;
    waiting_.clear();
    changed_.notify_all();
  }
  std::call_once(joined_, [this] { worker_.join(); });
}

void PickQueue::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return closed_ || !waiting_.empty(); });
    if (closed_) return;
    std::shared_ptr<Task> task = waiting_.front();
    waiting_.pop_front();
    task->state = Task::State::kRunning;
    task->waited = std::chrono::duration<double>(Clock::now() - task->queued_at).count();
    busy_ = true;
    changed_.notify_all();
    lock.unlock();
    try {
      task->job();  // the job answers its own errors; this only keeps the worker alive
    } catch (...) {
    }
    lock.lock();
    busy_ = false;
    task->state = Task::State::kDone;
    changed_.notify_all();
  }
}

}  // namespace flexsight
