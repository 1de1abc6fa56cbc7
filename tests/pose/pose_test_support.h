#pragma once
// Pictures of rendered parts for the pose tests.
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>

#include "host/render/raycaster.h"

namespace flexsight::pose_test_support {

// A grey picture of the part: brightness from the normal's turn to the camera (a lamp
// at the camera), on a dark background, so the silhouette and the creases show as edges.
inline cv::Mat picture(const RaycastImages& images) {
  cv::Mat grey(images.depth.size(), CV_8UC1, cv::Scalar(20));
  for (int y = 0; y < grey.rows; ++y) {
    for (int x = 0; x < grey.cols; ++x) {
      if (images.instance.at<int>(y, x) < 0) continue;
      const float facing = std::abs(images.geometric_normal.at<cv::Vec3f>(y, x)[2]);
      grey.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(60 + 180 * facing);
    }
  }
  return grey;
}

}  // namespace flexsight::pose_test_support
