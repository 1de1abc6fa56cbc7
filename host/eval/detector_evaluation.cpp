#include "host/eval/detector_evaluation.h"

#include <chrono>
#include <cstdint>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "host/detect/tiled_detection.h"
#include "host/io/input_error.h"
#include "host/io/progress_bar.h"
#include "host/runtime/compute_backend.h"

namespace flexsight {
namespace {

bool is_truth_category(const DetectionGroundTruth& truth, int category_id) {
  for (const DetectionCategory& category : truth.categories()) {
    if (category.id == category_id) return true;
  }
  return false;
}

std::string caption(const DetectionImage& image) {
  if (image.coco_id < 0) {
    return "scene " + std::to_string(image.scene_id) + ", im " + std::to_string(image.im_id);
  }
  std::string text = "image " + std::to_string(image.coco_id);
  if (image.scene_id >= 0 && image.im_id >= 0) {
    text += " (scene " + std::to_string(image.scene_id) + ", im " + std::to_string(image.im_id) + ")";
  }
  return text;
}

}  // namespace

DetectionResults run_detector(const std::string& model_path, const DetectionGroundTruth& truth,
                              const DetectorRunOptions& options) {
  if (options.threads > 0) cv::setNumThreads(options.threads);
  ComputeBackend backend(options.backend);
  SsdDetector detector(model_path, backend, options.detector);
  DetectionResults results;
  bool shares_a_category = false;
  for (const DetectorLabel& label : detector.labels()) {
    if (is_truth_category(truth, label.category_id)) {
      shares_a_category = true;
    } else if (truth.format() == DetectionGroundTruth::Format::bop) {
      results.extra_categories.push_back({label.category_id, label.name});
    } else {
      throw InputError(model_path, "detects category " + std::to_string(label.category_id) + " (" +
                                       label.name + "), which " + truth.source() +
                                       " does not have: a model for other parts");
    }
  }
  if (!shares_a_category) {
    throw InputError(model_path, "detects none of the objects of " + truth.source() + ": a model for other parts");
  }
  const TilingPlan tiling = fixed_tiling(options.tile);
  std::cerr << "eval-det: " << truth.images().size() << " images with " << model_path << "; "
            << detector.planned() << "\n";
  results.source = model_path;
  results.format = "model run by eval-det";
  if (tiling.tile > 0) {
    results.format += ", tiles of " + std::to_string(tiling.tile) + " px (stride " + std::to_string(tiling.stride) + ")";
  }
  std::optional<ProgressBar> progress;
  if (!options.quiet) progress.emplace(static_cast<std::int64_t>(truth.images().size()), "images");
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < truth.images().size(); ++i) {
    cv::Mat bgr;
    cv::cvtColor(truth.load_rgb(i), bgr, cv::COLOR_RGB2BGR);
    std::vector<DetectedBox> boxes;
    const auto detect = [&](const cv::Mat& part) { return detector.detect(part); };
    for (const ObjectDetection& found : detect_in_tiles(detect, bgr, tiling, options.detector.iou_threshold)) {
      DetectedBox box;
      box.category_id = found.category_id;
      box.bbox = {found.box[0], found.box[1], found.box[2] - found.box[0], found.box[3] - found.box[1]};
      box.score = found.score;
      boxes.push_back(box);
    }
    results.per_image.push_back(std::move(boxes));
    if (progress) progress->advance();
  }
  if (progress) progress->finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << "eval-det: detector at " << (seconds > 0 ? truth.images().size() / seconds : 0.0)
            << " images/s (reading included)\n";
  return results;
}

std::vector<MontageImage> montage_images(const DetectionGroundTruth& truth,
                                         const DetectionResults& detections, int count) {
  std::vector<MontageImage> images;
  for (std::size_t i = 0; i < truth.images().size() && static_cast<int>(i) < count; ++i) {
    MontageImage image;
    image.rgb = truth.load_rgb(i);
    image.caption = caption(truth.images()[i]);
    image.truth = truth.images()[i].truth;
    image.detections = detections.per_image[i];
    images.push_back(std::move(image));
  }
  return images;
}

}  // namespace flexsight
