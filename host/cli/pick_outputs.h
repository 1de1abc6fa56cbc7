#pragma once
// What `flexsight pick` writes: the ranked parts for the robot as JSON (docs/pick.md
// documents every key) and one picture with the boxes and the parts' outlines.
#include <string>

#include "host/cli/pick_pipeline.h"

namespace flexsight {

struct PickInputsDescription {
  std::string left, right, calib, model, templates, cad;
};

// The JSON document of a pick (docs/pick.md, "PICKS.json").
std::string pick_json(const PickResult& result, const PickInputsDescription& inputs);

// The left image with each detection's box and each posed part's outline and rank.
cv::Mat pick_picture(const cv::Mat& left_rgb8, const PickResult& result, const PoseModels& models);

}  // namespace flexsight
