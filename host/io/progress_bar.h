#pragma once
// A progress line for long runs (thousands of synthetic images): count, rate and time
// left on stderr. On a terminal it redraws one line; into a log file (a cluster job's
// output) it writes a line at every tenth of the work, so logs stay short.
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace flexsight {

class ProgressBar {
 public:
  // `total` items called `unit` ("images"); nothing is printed for total 0.
  ProgressBar(std::int64_t total, std::string unit);
  // Counts `count` more items done; thread-safe. Redraws at most five times a second.
  void advance(std::int64_t count = 1);
  // Draws the final state and ends the line.
  void finish();

 private:
  void draw(bool final_line);

  std::int64_t total_;
  std::string unit_;
  std::int64_t done_ = 0;
  int last_tenth_ = 0;
  bool terminal_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  std::mutex mutex_;
};

}  // namespace flexsight
