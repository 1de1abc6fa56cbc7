#pragma once
// The naming stage: a small classifier that names the part in a detector's box from a
// grey crop at its own resolution (the detector sees the part at 20-45 pixels of its
// 300x300 input and tells the 23 grey T-LESS parts apart poorly). Trained by
// scripts/detect/train_naming.py; the model folder (models/tless-namer):
//
//   model.onnx   input [1, 1, S, S]: the crop, standardised; output [1, C] logits
//   labels.txt   the detector's format (detector_model.h): "0 0 background", then the
//                class of output INDEX - 1 with its category id
//   model.json   {"task": "naming", "input_size": S, "color_order": "grey",
//                 "margin": 0.15, "normalisation": "per_crop_standardise", "std_floor": 0.02}
//
// The crop: the square around the box's centre, side max(w, h) x (1 + 2 margin), pixels
// outside the image repeated from its edge, grey, resized to S x S (area), then
// (x / 255 - mean) / (std + std_floor) over the crop.
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/detect/detector_model.h"

namespace flexsight {

struct NamerSettings {
  int input_size = 64;
  double margin = 0.15;
  double std_floor = 0.02;
};

class PartNamer {
 public:
  // Loads the folder of `model_path` and checks it before any image, each problem an
  // InputError naming the file: the ONNX missing, truncated or unreadable by OpenCV,
  // model.json missing or not a naming model's, labels.txt's classes other than the
  // network's outputs. The network runs once on a blank crop here.
  explicit PartNamer(const std::string& model_path);
  ~PartNamer();
  PartNamer(const PartNamer&) = delete;
  PartNamer& operator=(const PartNamer&) = delete;

  // Probabilities of each class (labels() order) for the part in `box` (x_min, y_min,
  // x_max, y_max in pixels) of `bgr` (CV_8UC3). InputError for another image type.
  std::vector<float> name(const cv::Mat& bgr, const float box[4]);
  // The crop name() classifies (CV_8UC1, S x S), from a grey image.
  cv::Mat crop(const cv::Mat& grey, const float box[4]) const;

  const std::vector<DetectorLabel>& labels() const;
  const NamerSettings& settings() const;
  const std::string& model_path() const;
  // Index into labels() of `category_id`, -1 when the namer does not know it.
  int class_of(int category_id) const;

  // InputError naming the namer's labels.txt unless it names the same parts as
  // `detector_labels` (a namer for other parts than the detector's).
  void require_same_parts(const std::vector<DetectorLabel>& detector_labels, const std::string& detector_path) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The shipped namer (<source>/models/tless-namer/model.onnx), FLEXSIGHT_NAMER_MODEL when set.
std::string default_namer_model_path();

}  // namespace flexsight
