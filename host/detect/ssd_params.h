#pragma once
// Every parameter of SSD post-processing, with its default and why. A `flexsight
// detect` command would expose each as --kebab-case-name (the names check() reports);
// check() rejects impossible values before any work starts.
#include <string>

#include "fallback/detect/ssd_reference.h"

namespace flexsight {

enum class SsdScoreFunction {
  // score = 1 / (1 + e^-logit) per class, independently: models trained with a sigmoid
  // (focal) loss, as the TF OD API's ssd_mobilenet_v2 configs (score_converter: SIGMOID).
  Sigmoid,
  // score = softmax over the background and the classes: models trained with a softmax
  // cross-entropy (the original SSD, torchvision's).
  Softmax,
};

// "sigmoid" or "softmax"; InputError naming `option` otherwise.
SsdScoreFunction parse_score_function(const std::string& text,
                                      const std::string& option = "option --score-function");
const char* score_function_name(SsdScoreFunction function);

struct SsdPostprocessParams {
  // How the class logits become scores; must match the model's training loss.
  SsdScoreFunction score_function = SsdScoreFunction::Sigmoid;
  // A class's score must exceed this for its box to be a candidate. 0.3 keeps a
  // detector's confident boxes and drops the long tail that only costs NMS time (the TF
  // OD API exports with 1e-8 for evaluation, where low scores still count for mAP).
  float score_threshold = 0.3f;
  // A candidate is suppressed when its IoU with a higher-ranked survivor of its class
  // exceeds this (the TF OD API ssd_mobilenet_v2 configs: 0.6).
  float iou_threshold = 0.6f;
  // Candidates of each class that enter NMS: the top_k best above the threshold
  // (torchvision's SSD "topk_candidates"; the TF OD API instead caps the survivors at
  // max_detections_per_class = 100). Bounds the suppression mask at top_k^2 bits a
  // class; at most SSD_MAX_TOP_K (1024).
  int top_k_per_class = 100;
  // Detections returned at most, the best of all classes' survivors (TF: 100).
  int max_detections = 100;
  // The box coder's scale factors (TF: 10, 10, 5, 5, i.e. variances 0.1 and 0.2); must
  // match the training's encoding.
  SsdBoxScale box_scale;

  // Throws InputError("option --score-threshold", ...) and the like for a threshold
  // outside [0, 1], a top_k outside 1..1024, max_detections below 1, or a scale factor
  // that is not a positive finite number.
  void check() const;
};

// The kernels' code of a score function (SSD_SCORE_SIGMOID, SSD_SCORE_SOFTMAX).
int score_function_code(SsdScoreFunction function);

}  // namespace flexsight
