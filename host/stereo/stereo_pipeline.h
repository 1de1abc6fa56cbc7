#pragma once
// The one entry point the CLI, the evaluator and the tests use to run the matcher.
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/stereo/stereo_params.h"

namespace flexsight {

struct StageTiming {
  std::string stage;
  double seconds = 0;
};

struct StereoResult {
  cv::Mat disparity;        // CV_32FC1, left view, post-processed (dense)
  cv::Mat raw_left;         // CV_32FC1, left view before post-processing
  cv::Mat raw_right;        // CV_32FC1, right view before post-processing
  cv::Mat planes_left;      // CV_32FC3 (a, b, c) per pixel after post-processing
  cv::Mat cost_left;        // CV_32FC1, matching cost of each raw left plane (finest level)
  std::vector<StageTiming> timings;
  double total_seconds() const;
};

// Called with a short description of the stage that starts ("level 2/4 iteration 1").
using ProgressCallback = std::function<void(const std::string&)>;

// Runs the reference matcher on an RGB8 pair of equal size. Throws InputError when
// params.check() fails or ndisp exceeds the image width.
StereoResult run_stereo(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                        const StereoParams& params, const ProgressCallback& progress = {});

}  // namespace flexsight
