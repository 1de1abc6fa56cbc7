#pragma once
// What a pick writes (`flexsight pick`, `eval-pick`): the ranked parts for the robot as
// JSON (docs/pick.md documents every key) and one picture with the boxes and the parts'
// outlines.
#include <string>
#include <vector>

#include "host/pick/pick_session.h"

namespace flexsight {

struct PickInputsDescription {
  std::string left, right, calib, model, templates, cad;
  std::string passive_left;  // empty: none given
  std::vector<int> parts;    // known-part mode's object ids; empty: every part
};

// The JSON document of a pick (docs/pick.md, "PICKS.json").
std::string pick_json(const PickResult& result, const PickInputsDescription& inputs);

// The left image with the picks' boxes and outlines and their ranks: the first pick, and
// the next ones while their pick_score is at least 0.5.
cv::Mat pick_picture(const cv::Mat& left_rgb8, const PickResult& result, const PoseModels& models);

}  // namespace flexsight
