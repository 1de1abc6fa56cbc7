#pragma once
// What GET /metrics reports: the requests answered, by HTTP status, and latency
// percentiles over the last answers, of the whole request, its wait in the queue and each
// stage of the pick. Safe to call from every server thread.
#include <cstddef>
#include <deque>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace flexsight {

// The q-quantile (0 < q <= 1) of `samples` by the nearest-rank rule: the smallest sample
// with at least q of all at or below it (p50 of 1..10 is 5, p90 9, p99 10). 0 when empty.
double nearest_rank_percentile(std::vector<double> samples, double q);

class LatencyMetrics {
 public:
  // Percentiles over the last `window` samples of each series.
  explicit LatencyMetrics(std::size_t window = 10000);

  // One request answered with HTTP `status`.
  void count_answer(int status);
  // One sample of `series` ("total", "queue_wait", "stereo", ...), in seconds.
  void add_seconds(const std::string& series, double seconds);

  // The median of `series`' window; 0 before its first sample.
  double median(const std::string& series) const;

  // {"requests": N, "answers": {"200": n, ...}, "errors": n (4xx and 5xx),
  //  "seconds": {series: {"count", "p50", "p90", "p99", "max"}}}
  std::string json() const;

 private:
  std::size_t window_;
  mutable std::mutex mutex_;
  std::map<int, long long> answers_;
  std::map<std::string, std::deque<double>> series_;
  std::map<std::string, long long> counts_;
};

}  // namespace flexsight
