#pragma once
// Poses the ground-truth boxes of a BOP data set (`flexsight pose DATASET --gt-boxes`):
// every part at least min_visib visible, several images at once (one estimator per
// thread), with the time of each stage.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "host/dataset/bop_pose_results.h"
#include "host/dataset/bop_reader.h"
#include "host/pose/pose_estimator.h"
#include "host/pose/pose_models.h"

namespace flexsight {

// How long the posing took: per part and stage, and the wall time of all parts with
// `threads` parts posed at once (the throughput a bin of parts sees).
struct PoseRunTiming {
  std::vector<PoseStageTimes> stages;
  double wall_s = 0.0;
  int threads = 1;
};

// Median milliseconds per stage over `times`: edges, search, refine, icp, score, total.
std::vector<std::pair<std::string, double>> median_stage_times(const std::vector<PoseStageTimes>& times);

// Whether `part`'s box is posed: at least min_visib visible, with a visible box.
bool poses_box(const PartAnnotation& part, double min_visib);

// The boxes of the first image_count images that are posed. InputError naming the
// scene's scene_gt.json for a part `models` does not have.
std::size_t count_boxes_to_pose(const BopReader& reader, std::size_t image_count, const PoseModels& models,
                                double min_visib);

struct DatasetPoses {
  std::vector<PoseEstimateRecord> records;  // in image order
  PoseRunTiming timing;
};

// Poses the boxes (`boxes` of them, for the progress line on stderr) on `threads`
// threads. InputError for an image without depth; the first error ends the run.
DatasetPoses pose_ground_truth_boxes(const BopReader& reader, std::size_t image_count, std::size_t boxes,
                                     const PoseModels& models, const PoseEstimatorParams& params, double min_visib,
                                     int threads);

}  // namespace flexsight
