#include "host/cli/pick_pipeline.h"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <exception>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Pixels of a part nearer than this to a nearer measured surface still count as seen:
// stereo depth is a few millimetres off at a metre.
constexpr double kVisibilityToleranceMm = 5.0;

}  // namespace

struct PickPipeline::Impl {
  PickSettings settings;
  ComputeBackend compute;
  StereoBackend stereo;
  SsdDetector detector;
  PoseModels models;

  explicit Impl(const PickSettings& s)
      : settings(s),
        compute(s.backend),
        stereo(compute),
        detector(s.model, compute, s.detector),
        models(s.templates, s.cad) {
    for (const DetectorLabel& label : detector.labels()) {
      if (!models.has(label.category_id)) {
        throw InputError(s.model, "detects object " + std::to_string(label.category_id) + " (" + label.name +
                                      "), which " + s.templates + " and " + s.cad +
                                      " do not hold: a detector for other parts than the CAD folder's");
      }
    }
  }
};

PickPipeline::PickPipeline(const PickSettings& settings) : impl_(std::make_unique<Impl>(settings)) {}
PickPipeline::~PickPipeline() = default;
const PoseModels& PickPipeline::models() const { return impl_->models; }

PickResult PickPipeline::run(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8, const StereoCamera& rig) {
  const PickSettings& settings = impl_->settings;
  PickResult result;
  result.camera = left_camera(rig, left_rgb8.size());

  auto start = Clock::now();
  ProgressCallback progress;
  if (!settings.quiet) progress = [](const std::string& stage) { std::cerr << "  stereo: " << stage << "\n"; };
  const StereoResult stereo = impl_->stereo.run(left_rgb8, right_rgb8, settings.stereo, progress, &result.stereo_path);
  result.disparity = stereo.disparity;
  result.seconds.stereo = seconds_since(start);

  start = Clock::now();
  const double to_mm = rig.metres_per_unit * 1000.0;
  result.depth_mm = cv::Mat(left_rgb8.size(), CV_32FC1, cv::Scalar(0));
  for (int y = 0; y < result.depth_mm.rows; ++y) {
    for (int x = 0; x < result.depth_mm.cols; ++x) {
      const double z = rig.depth(result.disparity.at<float>(y, x)) * to_mm;
      if (std::isfinite(z) && z > 0.0) result.depth_mm.at<float>(y, x) = static_cast<float>(z);
    }
  }
  result.floor_depth_mm = floor_depth_mm(result.depth_mm);
  result.seconds.depth = seconds_since(start);

  start = Clock::now();
  cv::Mat bgr;
  cv::cvtColor(left_rgb8, bgr, cv::COLOR_RGB2BGR);
  result.detections = impl_->detector.detect(bgr);
  result.detector_path = impl_->detector.planned();
  result.seconds.detection = seconds_since(start);

  // Each detection posed on its own, several at once (one estimator per thread).
  start = Clock::now();
  const cv::Rect image_rect(cv::Point(), bgr.size());
  std::vector<PickCandidate> candidates(result.detections.size());
  std::vector<bool> posed(result.detections.size(), false);
  std::exception_ptr failure;
  const int threads = settings.threads > 0 ? settings.threads : omp_get_max_threads();
#pragma omp parallel num_threads(threads)
  {
    PoseEstimator estimator(settings.pose);
#pragma omp for schedule(dynamic)
    for (int i = 0; i < static_cast<int>(result.detections.size()); ++i) {
      try {
        const ObjectDetection& d = result.detections[i];
        const cv::Rect box = cv::Rect(cv::Point(static_cast<int>(std::floor(d.box[0])), static_cast<int>(std::floor(d.box[1]))),
                                      cv::Point(static_cast<int>(std::ceil(d.box[2])), static_cast<int>(std::ceil(d.box[3])))) &
                             image_rect;
        if (box.width < 4 || box.height < 4) continue;
        const PoseModel& model = impl_->models.model(d.category_id, settings.model);
        PoseEstimate estimate;
        try {
          estimate = estimator.estimate(model, bgr, result.depth_mm, result.camera, box);
        } catch (const InputError&) {
          continue;  // a box without any measured depth: nothing to pose it with
        }
        PickCandidate& c = candidates[i];
        c.obj_id = d.category_id;
        c.pose = estimate.pose;
        c.box = box;
        c.detection_score = d.score;
        c.pose_score = estimate.score;
        c.times = estimate.times;
        c.visible_fraction = visible_fraction(model.mesh, estimate.pose, result.camera, result.depth_mm,
                                              kVisibilityToleranceMm);
        c.height_mm = result.floor_depth_mm > 0.0 ? result.floor_depth_mm - estimate.pose.t.z() : 0.0;
        posed[i] = true;
      } catch (...) {
#pragma omp critical
        if (!failure) failure = std::current_exception();
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (posed[i]) result.picks.push_back(candidates[i]);
  }
  result.seconds.pose = seconds_since(start);

  start = Clock::now();
  rank_picks(result.picks);
  result.seconds.ranking = seconds_since(start);
  return result;
}

}  // namespace flexsight
