#pragma once
// A picture of a point cloud from a viewpoint beside the camera, so a reader sees the
// 3D shape (and the normals, through shading) without a viewer.
#include <opencv2/core.hpp>

#include "host/geometry/point_cloud.h"

namespace flexsight {

struct CloudView {
  int width = 800;
  int height = 600;
  double yaw_degrees = 30;    // turn about the cloud's centre, around the image's y axis
  double pitch_degrees = -15;  // then around the x axis (negative: look from above)
  double shading = 0.6;       // 0: colours only; 1: lit by the normals only
};

// RGB8 image. Points are splatted with a depth test; the virtual camera looks at the
// cloud's median point from the real camera's distance, rotated by the view's angles.
cv::Mat render_point_cloud(const PointCloud& cloud, const CloudView& view = {});

}  // namespace flexsight
