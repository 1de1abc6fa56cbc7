// /metrics' counts and percentiles (host/service/latency_metrics.h): the nearest-rank rule
// on known samples, the window that keeps only the last samples, and the JSON report.
#include "host/service/latency_metrics.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <numeric>

namespace flexsight {
namespace {

TEST(LatencyMetrics, NearestRankPercentiles) {
  std::vector<double> one_to_ten(10);
  std::iota(one_to_ten.begin(), one_to_ten.end(), 1.0);
  std::vector<double> shuffled = {7, 3, 10, 1, 9, 2, 8, 5, 4, 6};
  for (const auto& samples : {one_to_ten, shuffled}) {
    EXPECT_EQ(nearest_rank_percentile(samples, 0.50), 5.0);
    EXPECT_EQ(nearest_rank_percentile(samples, 0.90), 9.0);
    EXPECT_EQ(nearest_rank_percentile(samples, 0.99), 10.0);
    EXPECT_EQ(nearest_rank_percentile(samples, 0.10), 1.0);
  }
  std::vector<double> hundred(100);
  std::iota(hundred.begin(), hundred.end(), 1.0);
  EXPECT_EQ(nearest_rank_percentile(hundred, 0.99), 99.0);
  EXPECT_EQ(nearest_rank_percentile(hundred, 0.5), 50.0);
  EXPECT_EQ(nearest_rank_percentile({4.0}, 0.99), 4.0);
  EXPECT_EQ(nearest_rank_percentile({}, 0.5), 0.0);
}

TEST(LatencyMetrics, CountsAnswersAndKeepsTheLastSamples) {
  LatencyMetrics metrics(4);
  for (int status : {200, 200, 400, 413, 503, 200}) metrics.count_answer(status);
  for (double s : {100.0, 1.0, 2.0, 3.0, 4.0}) metrics.add_seconds("total", s);  // 100 leaves the window
  metrics.add_seconds("stereo", 0.5);
  const nlohmann::json report = nlohmann::json::parse(metrics.json());
  EXPECT_EQ(report.at("requests").get<int>(), 6);
  EXPECT_EQ(report.at("errors").get<int>(), 3);
  EXPECT_EQ(report.at("answers").at("200").get<int>(), 3);
  EXPECT_EQ(report.at("answers").at("413").get<int>(), 1);
  const nlohmann::json& total = report.at("seconds").at("total");
  EXPECT_EQ(total.at("count").get<int>(), 5) << "every sample counted";
  EXPECT_EQ(total.at("p50").get<double>(), 2.0);
  EXPECT_EQ(total.at("p99").get<double>(), 4.0);
  EXPECT_EQ(total.at("max").get<double>(), 4.0);
  EXPECT_EQ(metrics.median("total"), 2.0);
  EXPECT_EQ(metrics.median("pose"), 0.0);
  EXPECT_EQ(report.at("seconds").at("stereo").at("p90").get<double>(), 0.5);
}

}  // namespace
}  // namespace flexsight
