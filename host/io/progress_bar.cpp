#include "host/io/progress_bar.h"

#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <sstream>

namespace flexsight {
namespace {

std::string clock_text(double seconds) {
  const long total = static_cast<long>(seconds + 0.5);
  char text[32];
  std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", total / 3600, total / 60 % 60, total % 60);
  return text;
}

}  // namespace

ProgressBar::ProgressBar(std::int64_t total, std::string unit)
    : total_(total),
      unit_(std::move(unit)),
      terminal_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

void ProgressBar::advance(std::int64_t count) {
  std::lock_guard<std::mutex> lock(mutex_);
  done_ += count;
  if (total_ <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (terminal_) {
    if (now - last_draw_ >= std::chrono::milliseconds(200)) draw(false);
  } else {
    const int tenth = static_cast<int>(10 * done_ / total_);
    if (tenth > last_tenth_ && done_ < total_) {
      last_tenth_ = tenth;
      draw(false);
    }
  }
}

void ProgressBar::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_ || total_ <= 0) return;
  finished_ = true;
  draw(true);
}

void ProgressBar::draw(bool final_line) {
  last_draw_ = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(last_draw_ - start_).count();
  const double rate = seconds > 0 ? done_ / seconds : 0.0;
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(kWidth * done_ / total_);
  std::ostringstream line;
  line << "[" << std::string(filled, '#') << std::string(kWidth - filled, '.') << "] " << done_
       << "/" << total_ << " " << unit_ << "  ";
  line.precision(1);
  line << std::fixed << rate << " " << unit_ << "/s  ";
  if (final_line) {
    line << "took " << clock_text(seconds);
  } else {
    line << "left " << (rate > 0 ? clock_text((total_ - done_) / rate) : std::string("?"));
  }
  if (terminal_) {
    std::cerr << "\r" << line.str() << (final_line ? "\n" : "") << std::flush;
  } else {
    std::cerr << line.str() << "\n" << std::flush;
  }
}

}  // namespace flexsight
