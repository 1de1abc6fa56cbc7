#pragma once
// The tables `flexsight stereo` prints on stdout: the time per stage, the device time per
// kernel and the memory (--profile), and the scores against a ground truth (--gt).
#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/runtime/kernel_timing.h"
#include "host/stereo/stereo_pipeline.h"

namespace flexsight {

// `used`: the path that ran (the table's heading).
void print_stage_times(const std::string& used, const StereoResult& result);

// --profile: device time per kernel, from the OpenCL events of the run.
void print_kernel_timings(const std::vector<opencl::KernelTiming>& timings);

// --profile: memory against the yardstick, the input pair (RGB8) and the planes
// of both views (a, b, c as float): 30 bytes per pixel.
void print_memory(size_t device_bytes, int width, int height);

// Bad-N and average error against `gt` (`mask`: non-occluded pixels, may be empty);
// `confidence` may be empty (OpenCV's matchers have none).
void print_scores(const cv::Mat& disparity, const cv::Mat& confidence, const cv::Mat& gt, const cv::Mat& mask);

}  // namespace flexsight
