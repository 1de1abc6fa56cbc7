#pragma once
// The image form of `flexsight pose` (pose_image_form.cpp).
#include <string>
#include <vector>

#include "host/pose/pose_estimator.h"

namespace flexsight {

int run_pose_image_form(const std::string& image_path, std::vector<std::string>& args,
                        const std::string& cad_dir, const PoseEstimatorParams& params);

}  // namespace flexsight
