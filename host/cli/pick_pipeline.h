#pragma once
// The whole job of `flexsight pick` on one rectified pair: stereo depth, detection, the
// pose in each box, and the ranked list for the robot. One ComputeBackend (one OpenCL
// context) serves the matcher and the detector's post-processing.
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/cli/backend.h"
#include "host/cli/pose_inputs.h"
#include "host/detect/ssd_detector.h"
#include "host/geometry/stereo_camera.h"
#include "host/pick/pick_ranking.h"
#include "host/stereo/stereo_params.h"

namespace flexsight {

struct PickSettings {
  StereoParams stereo;
  BackendOptions backend;
  SsdDetectorOptions detector;
  PoseEstimatorParams pose;
  std::string model;      // the detector (resolved path)
  std::string templates;  // flexsight pose-templates' file
  std::string cad;        // the CAD folder the templates were made from
  int threads = 0;        // parts posed at once (0 = all cores)
  bool quiet = false;
};

struct PickStageSeconds {
  double stereo = 0.0, depth = 0.0, detection = 0.0, pose = 0.0, ranking = 0.0;
  double total() const { return stereo + depth + detection + pose + ranking; }
};

struct PickResult {
  cv::Mat disparity;  // CV_32FC1, left view
  cv::Mat depth_mm;   // CV_32FC1, 0 where unknown
  PinholeCamera camera;
  double floor_depth_mm = 0.0;
  std::vector<ObjectDetection> detections;
  std::vector<PickCandidate> picks;  // ranked, best first
  PickStageSeconds seconds;
  std::string stereo_path, detector_path;  // which backend each ran on
};

class PickPipeline {
 public:
  // Loads and checks everything before any image: the detector (its files), the
  // templates against the CAD folder, and that every class the detector knows has a
  // model and templates (else an InputError naming --model). Builds the OpenCL parts.
  explicit PickPipeline(const PickSettings& settings);
  ~PickPipeline();
  PickPipeline(const PickPipeline&) = delete;
  PickPipeline& operator=(const PickPipeline&) = delete;

  const PoseModels& models() const;
  // `left`, `right`: RGB8 of one size; `rig`: their calibration at that size.
  PickResult run(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8, const StereoCamera& rig);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};


}  // namespace flexsight
