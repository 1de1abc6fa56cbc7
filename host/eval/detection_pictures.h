#pragma once
// The pictures of a detection evaluation: the precision-recall curves behind the APs,
// and a montage of images with their ground truth and detections, to see at a glance
// what the numbers mean (boxes off by a few pixels, a class always missed, ...).
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/eval/detection_metrics.h"

namespace flexsight {

// RGB (CV_8UC3): every class's precision envelope against recall (VOC matching at
// scores.iou_threshold) in its own colour, the mean over classes thick and black, axes
// labelled, a legend with each class's AP.
cv::Mat draw_pr_curves(const DetectionScores& scores);

struct MontageImage {
  cv::Mat rgb;          // CV_8UC3, RGB
  std::string caption;  // which image it is ("scene 1, im 42")
  std::vector<TruthBox> truth;
  std::vector<DetectedBox> detections;
};

struct MontageOptions {
  // Detections scored below this are left out: a detector's many low-score boxes would
  // hide the rest.
  double min_score = 0.3;
  int columns = 4;
  int tile_width = 320;  // each image scaled to this width, its aspect kept
};

// RGB (CV_8UC3): the images in a grid, row-major in the given order, ground truth in
// green, detections at or above min_score in magenta labelled "class score", a caption
// under each and a legend on top; empty when `images` is.
cv::Mat draw_detection_montage(const std::vector<MontageImage>& images,
                               const MontageOptions& options = {});

}  // namespace flexsight
