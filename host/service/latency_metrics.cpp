#include "host/service/latency_metrics.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

namespace flexsight {

double nearest_rank_percentile(std::vector<double> samples, double q) {
  if (samples.empty()) return 0.0;
  const std::size_t n = samples.size();
  const std::size_t rank = std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(q * static_cast<double>(n) - 1e-9)), 1, n);
  std::nth_element(samples.begin(), samples.begin() + (rank - 1), samples.end());
  return samples[rank - 1];
}

LatencyMetrics::LatencyMetrics(std::size_t window) : window_(std::max<std::size_t>(1, window)) {}

void LatencyMetrics::count_answer(int status) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++answers_[status];
}

void LatencyMetrics::add_seconds(const std::string& series, double seconds) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::deque<double>& samples = series_[series];
  samples.push_back(seconds);
  if (samples.size() > window_) samples.pop_front();
  ++counts_[series];
}

double LatencyMetrics::median(const std::string& series) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = series_.find(series);
  if (it == series_.end()) return 0.0;
  return nearest_rank_percentile(std::vector<double>(it->second.begin(), it->second.end()), 0.5);
}

std::string LatencyMetrics::json() const {
  std::lock_guard<std::mutex> lock(mutex_);
  nlohmann::json answers = nlohmann::json::object(), seconds = nlohmann::json::object();
  long long requests = 0, errors = 0;
  for (const auto& [status, count] : answers_) {
    answers[std::to_string(status)] = count;
    requests += count;
    if (status >= 400) errors += count;
  }
  for (const auto& [name, deque] : series_) {
    const std::vector<double> samples(deque.begin(), deque.end());
    seconds[name] = {{"count", counts_.at(name)},
                     {"p50", nearest_rank_percentile(samples, 0.50)},
                     {"p90", nearest_rank_percentile(samples, 0.90)},
                     {"p99", nearest_rank_percentile(samples, 0.99)},
                     {"max", *std::max_element(samples.begin(), samples.end())}};
  }
  return nlohmann::json{{"requests", requests}, {"answers", answers}, {"errors", errors}, {"seconds", seconds}}.dump() + "\n";
}

}  // namespace flexsight
