#pragma once
// The detector's side of `flexsight eval-det`: the detector run on every image of a data
// set's ground truth, and the images of the montage with their boxes.
#include <string>
#include <vector>

#include "host/detect/ssd_detector.h"
#include "host/eval/detection_ground_truth.h"
#include "host/eval/detection_pictures.h"
#include "host/eval/detection_results_reader.h"
#include "host/runtime/device_options.h"

namespace flexsight {

struct DetectorRunOptions {
  SsdDetectorOptions detector;
  BackendOptions backend;
  int threads = 0;     // OpenCV's threads (0: its default)
  bool quiet = false;  // no progress line
  // Square tiles of this many pixels (host/detect/tiled_detection.h, fixed_tiling), the
  // boxes merged by per-class NMS at detector.iou_threshold; 0: the whole image.
  int tile = 0;
};

// The detector of `model_path` on every image of `truth`. A model that knows a category
// a COCO data set lacks, or none of a BOP folder's, was trained for other parts: refused
// (InputError naming the model) before any image runs. A BOP folder names only the
// objects its scenes show (a bin holds a few of the 23 parts): the model's other classes
// come back in extra_categories.
DetectionResults run_detector(const std::string& model_path, const DetectionGroundTruth& truth,
                              const DetectorRunOptions& options);

// The first `count` images with their boxes; reads their pictures, so a missing image
// file fails here, before anything is written.
std::vector<MontageImage> montage_images(const DetectionGroundTruth& truth, const DetectionResults& detections,
                                         int count);

}  // namespace flexsight
