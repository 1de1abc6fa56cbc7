#pragma once
// Pictures of poses: each part's outline, as its CAD model projects at the pose, drawn
// over the image, so a pose can be judged at a glance.
#include <opencv2/core.hpp>
#include <vector>

#include "host/render/mesh.h"
#include "host/render/raycaster.h"

namespace flexsight {

struct PosedPart {
  std::shared_ptr<const Mesh> mesh;
  Pose pose;
  cv::Scalar colour;  // BGR
  std::string label;  // drawn beside the outline ("" for none)
};

// Draws onto `bgr` (CV_8UC3, the camera's image size) the outline of each part's
// silhouette and its inner creases seen from `camera`, each part as if alone.
void draw_posed_parts(cv::Mat& bgr, const std::vector<PosedPart>& parts, const PinholeCamera& camera);

}  // namespace flexsight
