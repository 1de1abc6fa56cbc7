#pragma once
// The stereo benchmark run (`flexsight eval`): the matcher, an OpenCV peer or results
// computed elsewhere scored on each scene of a benchmark folder against its ground
// truth, with repeated runs timed by their median, the pictures of each scene, and the
// report of them all (report.h).
#include <optional>
#include <string>
#include <vector>

#include "host/eval/dataset.h"
#include "host/eval/report.h"
#include "host/runtime/device_options.h"
#include "host/stereo/opencv_stereo.h"
#include "host/stereo/stereo_params.h"

namespace flexsight {

struct StereoEvalOptions {
  std::string results_dir;  // "" = run the matcher
  std::string out_dir = "eval_out";
  float max_disp_color = 0;              // 0 = each scene's ndisp
  StereoParams params;
  std::optional<OpenCvMatcher> opencv;  // an OpenCV peer instead of the matcher
  int repeat = 1;                        // runs per scene; the median time is reported
  // The matcher's parameters as the report lists them (when the matcher runs).
  std::vector<ReportParameter> parameters;
};

// Everything that can be checked cheaply before the first scene is matched: each scene
// has ground truth, and a result file when results are read from files. InputError
// naming the file otherwise.
void check_scenes_before_running(const std::vector<Scene>& scenes, const StereoEvalOptions& options);

// Scores every scene (its disparity and pictures written to options.out_dir, which must
// exist) and returns the report; the matcher runs on `backend`'s device, chosen and
// built once for every scene. Progress goes to stderr.
EvalReport evaluate_stereo_scenes(const std::string& dataset_root, const std::vector<Scene>& scenes,
                                  const StereoEvalOptions& options, const BackendOptions& backend);

}  // namespace flexsight
