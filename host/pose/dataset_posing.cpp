#include "host/pose/dataset_posing.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <opencv2/imgproc.hpp>

#include "host/io/input_error.h"
#include "host/io/progress_bar.h"

namespace flexsight {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// The image's parts posed by one estimator; each record's time_s is the image's time.
void pose_image(PoseEstimator& estimator, const BopReader& reader, std::size_t i, const PoseModels& models,
                double min_visib, ProgressBar& progress, std::vector<PoseEstimateRecord>& records,
                std::vector<PoseStageTimes>& times) {
  const AnnotatedImage image = reader.load(i);
  if (image.depth.empty()) throw InputError(reader.scene_dir(i), "has no depth/ image for image " + std::to_string(image.im_id));
  cv::Mat bgr;
  cv::cvtColor(image.rgb, bgr, cv::COLOR_RGB2BGR);
  const PinholeCamera camera = camera_of(image);
  const auto start = std::chrono::steady_clock::now();
  for (const PartAnnotation& part : image.parts) {
    if (!poses_box(part, min_visib)) continue;
    const cv::Rect box(part.bbox_visib.x, part.bbox_visib.y, part.bbox_visib.width, part.bbox_visib.height);
    const PoseEstimate estimate = estimator.estimate(models.model(part.obj_id, "data set"), bgr, image.depth, camera, box);
    records.push_back(pose_estimate_record(image.scene_id, image.im_id, part.obj_id, estimate.score,
                                           estimate.pose.R, estimate.pose.t));
    times.push_back(estimate.times);
    progress.advance();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (auto& record : records) record.time_s = seconds;
}

}  // namespace

std::vector<std::pair<std::string, double>> median_stage_times(const std::vector<PoseStageTimes>& times) {
  std::vector<double> edges, search, refine, icp, score, total;
  for (const auto& t : times) {
    edges.push_back(t.edges_ms);
    search.push_back(t.search_ms);
    refine.push_back(t.refine_ms);
    icp.push_back(t.icp_ms);
    score.push_back(t.score_ms);
    total.push_back(t.total_ms());
  }
  return {{"edges", median(edges)}, {"search", median(search)}, {"refine", median(refine)},
          {"icp", median(icp)},     {"score", median(score)},   {"total", median(total)}};
}

bool poses_box(const PartAnnotation& part, double min_visib) {
  return part.visib_fract >= min_visib && !part.bbox_visib.empty();
}

std::size_t count_boxes_to_pose(const BopReader& reader, std::size_t image_count, const PoseModels& models,
                                double min_visib) {
  std::size_t boxes = 0;
  for (std::size_t i = 0; i < image_count; ++i) {
    for (const PartAnnotation& part : reader.record(i).parts) {
      if (!poses_box(part, min_visib)) continue;
      models.model(part.obj_id, reader.scene_dir(i) + "/scene_gt.json");
      ++boxes;
    }
  }
  return boxes;
}

DatasetPoses pose_ground_truth_boxes(const BopReader& reader, std::size_t image_count, std::size_t boxes,
                                     const PoseModels& models, const PoseEstimatorParams& params, double min_visib,
                                     int threads) {
  std::vector<std::vector<PoseEstimateRecord>> per_image(image_count);
  std::vector<std::vector<PoseStageTimes>> times(image_count);
  ProgressBar progress(static_cast<std::int64_t>(boxes), "parts");
  std::exception_ptr failure;
  const auto posing_start = std::chrono::steady_clock::now();
#pragma omp parallel num_threads(threads)
  {
    PoseEstimator estimator(params);
#pragma omp for schedule(dynamic)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(image_count); ++i) {
      try {
        pose_image(estimator, reader, i, models, min_visib, progress, per_image[i], times[i]);
      } catch (...) {
#pragma omp critical
        if (!failure) failure = std::current_exception();
      }
    }
  }
  progress.finish();
  if (failure) std::rethrow_exception(failure);
  DatasetPoses poses;
  poses.timing.threads = threads;
  poses.timing.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - posing_start).count();
  for (std::size_t i = 0; i < image_count; ++i) {
    poses.records.insert(poses.records.end(), per_image[i].begin(), per_image[i].end());
    poses.timing.stages.insert(poses.timing.stages.end(), times[i].begin(), times[i].end());
  }
  return poses;
}

}  // namespace flexsight
