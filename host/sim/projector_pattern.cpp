#include "host/sim/projector_pattern.h"

#include <cmath>

namespace flexsight {

ProjectorCalib projector_calib(const StereoRig& rig, const ProjectorSettings& settings) {
  ProjectorCalib projector;
  const double f = rig.focal();
  const double half_field = std::tan(settings.fov_degrees * M_PI / 360.0);
  const int size = 2 * int(std::ceil(f * half_field)) + 1;
  const double centre = (size - 1) / 2.0;
  projector.K = {f, 0, centre, 0, f, centre, 0, 0, 1};
  projector.width = projector.height = size;
  const Eigen::Vector3d apex = rig.projector_in_left();
  projector.t = {0.0 - apex.x(), 0.0 - apex.y(), 0.0 - apex.z()};  // no "-0" in the file
  projector.pattern = kProjectorPatternFile;
  return projector;
}

cv::Mat render_pattern_image(const DotPattern& pattern, const ProjectorCalib& projector) {
  const double fx = projector.K[0], cx = projector.K[2], fy = projector.K[4], cy = projector.K[5];
  cv::Mat image(projector.height, projector.width, CV_8UC1);
#pragma omp parallel for schedule(static)
  for (int v = 0; v < image.rows; ++v) {
    for (int u = 0; u < image.cols; ++u) {
      const double x = (u - cx) / fx, y = (v - cy) / fy;
      // The pixel's footprint in angle: its width 1/f at the centre, narrower off-axis.
      const double footprint = 1.0 / (fx * (1.0 + x * x)) / std::sqrt(12.0);
      const double light = pattern.intensity({std::atan(x), std::atan(y)}, footprint);
      image.at<std::uint8_t>(v, u) = cv::saturate_cast<std::uint8_t>(255.0 * light);
    }
  }
  return image;
}

}  // namespace flexsight
