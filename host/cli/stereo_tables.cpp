#include "host/cli/stereo_tables.h"

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <iostream>

#include "host/eval/confidence_depth_metrics.h"
#include "host/eval/metrics.h"

namespace flexsight {

void print_stage_times(const std::string& used, const StereoResult& result) {
  std::printf("| stage (%s) | seconds |\n|---|---|\n", used.c_str());
  for (const StageTiming& t : result.timings) std::printf("| %s | %.3f |\n", t.stage.c_str(), t.seconds);
  std::printf("| total | %.3f |\n", result.total_seconds());
}

void print_kernel_timings(const std::vector<opencl::KernelTiming>& timings) {
  if (timings.empty()) {
    std::cerr << "note: --profile: the reference path ran, so there are no kernel times\n";
    return;
  }
  std::printf("\n| kernel | calls | total ms | mean ms |\n|---|---|---|---|\n");
  int calls = 0;
  double seconds = 0;
  for (const opencl::KernelTiming& t : timings) {
    std::printf("| %s | %d | %.3f | %.3f |\n", t.kernel.c_str(), t.launches, t.seconds * 1e3,
                t.launches > 0 ? t.seconds * 1e3 / t.launches : 0.0);
    calls += t.launches;
    seconds += t.seconds;
  }
  std::printf("| all kernels | %d | %.3f | %.3f |\n", calls, seconds * 1e3,
              calls > 0 ? seconds * 1e3 / calls : 0.0);
}

void print_memory(size_t device_bytes, int width, int height) {
  const double input_and_planes = 30.0 * width * height;
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  const double rss = static_cast<double>(usage.ru_maxrss) * 1024.0;  // Linux: kilobytes
  if (device_bytes > 0) {
    std::printf("device memory: %.1f MiB at most in buffers = %.1f x the input pair and its "
                "planes (%.1f MiB)\n",
                device_bytes / 1048576.0, device_bytes / input_and_planes,
                input_and_planes / 1048576.0);
  }
  std::printf("process peak resident memory: %.1f MiB (with the OpenCL runtime's own)\n",
              rss / 1048576.0);
}

void print_scores(const cv::Mat& disparity, const cv::Mat& confidence, const cv::Mat& gt, const cv::Mat& mask) {
  SceneScores scores = evaluate_disparity(disparity, gt, mask);
  std::printf("\n| pixels | bad 0.5 | bad 1 | bad 2 | bad 3 | bad 4 | avg err | density |\n"
              "|---|---|---|---|---|---|---|---|\n");
  auto row = [](const char* name, const ErrorStats& s) {
    char error[32] = "n/a";
    if (std::isfinite(s.avg_error)) std::snprintf(error, sizeof error, "%.3f px", s.avg_error);
    std::printf("| %s | %.2f %% | %.2f %% | %.2f %% | %.2f %% | %.2f %% | %s | %.1f %% |\n", name,
                s.bad_percent[0], s.bad_percent[1], s.bad_percent[2], s.bad_percent[3], s.bad_percent[4], error,
                s.density_percent);
  };
  row("all", scores.all);
  if (!mask.empty()) row("nonocc", scores.nonocc);
  std::printf("(errors in pixels at this resolution; pixels without a result count as bad)\n");
  const ConfidentStats confident = evaluate_confident(disparity, gt, confidence);
  if (confident.available) {
    std::printf("confidence: sparsification AUC %.2f %% bad-2 (optimum %.2f %%); C >= 0.5 keeps "
                "%.1f %% of the pixels at %.2f %% bad-2, C >= 0.75 %.1f %% at %.2f %%\n",
                confident.sparsification_auc_percent, confident.optimal_auc_percent,
                confident.density_percent[1], confident.bad2_percent[1],
                confident.density_percent[2], confident.bad2_percent[2]);
  }
}

}  // namespace flexsight
