#pragma once
// What SSD post-processing returns: one box per detected object, in the frame of the
// network's input, and the raw outputs it is computed from.
#include <vector>

#include "kernels/detect/ssd_math.h"

namespace flexsight {

struct Detection {
  // Foreground class, 0-based: the class of logit column class_id + 1 (column 0 is the
  // background), i.e. the index into the model's class-name list without "background".
  int class_id = 0;
  float score = 0.0f;
  // x_min, y_min, x_max, y_max, normalised to [0, 1] of the network input (the image as
  // resized for it); detection_in_pixels scales them.
  float box[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  // The anchor the box was decoded from (ties in score are broken by it; for debugging).
  int anchor = 0;
};

// The network's two outputs for one image, as float arrays in row-major order (OpenCV
// DNN's output Mats, ONNX Runtime's tensors), not owned.
struct SsdOutputs {
  // anchors x 4: (ty, tx, th, tw), the TF OD API's encoding.
  const float* box_encodings = nullptr;
  // anchors x (classes + 1): column 0 the background.
  const float* class_logits = nullptr;
  int anchors = 0;
  // Foreground classes (logit columns minus one).
  int classes = 0;
};

Detection detection_from_record(const SsdDetectionRecord& record);
std::vector<Detection> detections_from_records(const std::vector<SsdDetectionRecord>& records);

// The box in pixels of an image of width x height (x times width, y times height); the
// caller undoes any letterboxing first.
Detection detection_in_pixels(const Detection& detection, int width, int height);

}  // namespace flexsight
