#pragma once
// Ground-truth and detected boxes written in one line each, for the detection scoring
// tests (test_detection_metrics.cpp, test_detection_breakdown.cpp).
#include <vector>

#include "host/eval/detection_metrics.h"

namespace flexsight::detection_boxes {

constexpr double kTight = 1e-12;

inline TruthBox truth(int category, double x, double y, double w, double h, bool crowd = false) {
  TruthBox box;
  box.category_id = category;
  box.bbox = {x, y, w, h};
  box.area = w * h;
  box.crowd = crowd;
  return box;
}

inline DetectedBox detected(int category, double x, double y, double w, double h, double score) {
  DetectedBox box;
  box.category_id = category;
  box.bbox = {x, y, w, h};
  box.score = score;
  return box;
}

inline const std::vector<DetectionCategory> kTwoClasses = {{1, "one"}, {2, "two"}};

}  // namespace flexsight::detection_boxes
