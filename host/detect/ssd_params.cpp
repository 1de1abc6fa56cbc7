#include "host/detect/ssd_params.h"

#include <cmath>
#include <sstream>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

void require(bool ok, const char* option, const std::string& problem) {
  if (!ok) throw InputError(std::string("option --") + option, problem);
}

std::string number(float value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

bool in_unit_interval(float value) { return value >= 0.0f && value <= 1.0f; }  // false for NaN

}  // namespace

SsdScoreFunction parse_score_function(const std::string& text, const std::string& option) {
  if (text == "sigmoid") return SsdScoreFunction::Sigmoid;
  if (text == "softmax") return SsdScoreFunction::Softmax;
  throw InputError(option, "expected sigmoid or softmax, got '" + text + "'");
}

const char* score_function_name(SsdScoreFunction function) {
  return function == SsdScoreFunction::Softmax ? "softmax" : "sigmoid";
}

int score_function_code(SsdScoreFunction function) {
  return function == SsdScoreFunction::Softmax ? SSD_SCORE_SOFTMAX : SSD_SCORE_SIGMOID;
}

void SsdPostprocessParams::check() const {
  require(in_unit_interval(score_threshold), "score-threshold",
          "must lie in [0, 1], got " + number(score_threshold));
  require(in_unit_interval(iou_threshold), "iou-threshold",
          "must lie in [0, 1], got " + number(iou_threshold));
  require(top_k_per_class >= 1 && top_k_per_class <= SSD_MAX_TOP_K, "top-k",
          "must be in 1.." + std::to_string(SSD_MAX_TOP_K) + ", got " +
              std::to_string(top_k_per_class));
  require(max_detections >= 1, "max-detections",
          "must be at least 1, got " + std::to_string(max_detections));
  const float scales[4] = {box_scale.y, box_scale.x, box_scale.h, box_scale.w};
  for (float scale : scales) {
    require(std::isfinite(scale) && scale > 0.0f, "box-scale",
            "scale factors must be positive, got " + number(box_scale.y) + "," +
                number(box_scale.x) + "," + number(box_scale.h) + "," + number(box_scale.w));
  }
}

}  // namespace flexsight
