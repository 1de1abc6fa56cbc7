#pragma once
// From a disparity map (and, when the matcher gave them, its per-pixel planes) to the
// 3D products a robot cell consumes: a depth map and a colored point cloud with normals
// and confidences.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/geometry/stereo_camera.h"

namespace flexsight {

struct PointCloud {
  std::vector<Eigen::Vector3f> points;   // in the camera's unit, left camera frame
  std::vector<Eigen::Vector3f> normals;  // unit, facing the camera
  std::vector<cv::Vec3b> colors;         // RGB
  std::vector<float> confidence;         // empty when unknown
  std::vector<int> pixel;                // y * width + x of each point
  std::string unit;
  size_t size() const { return points.size(); }
};

// Which pixels become points. Pixels without a disparity (NaN/inf/negative) or
// behind infinity never do.
struct CloudFilter {
  float min_confidence = 0.0f;  // keep pixels with confidence >= this (needs a map)
  double min_depth = 0.0;       // in the camera's unit; 0 = no lower bound
  double max_depth = 0.0;       // 0 = no upper bound
};

// Where each point's normal comes from.
struct NormalOptions {
  // Half size of the window of the least-squares disparity-plane fit; 0 takes the
  // matcher's per-pixel plane as it is. The fit is the default because a plane's slant
  // is weakly determined by one 35-pixel window (at a disparity of 13 px an error of
  // 0.01 px/px in slope turns the normal by about 10 degrees), while a fit over the
  // final disparities of the neighbourhood averages that noise out.
  int fit_radius = 8;
  // Neighbours more than this many pixels of disparity off the pixel's own plane (or,
  // without planes, its disparity) are left out of the fit, so it does not straddle
  // depth edges.
  float inlier_disparity = 1.0f;
};

// `disparity` CV_32FC1; `left_rgb` CV_8UC3 of the same size (RGB order); `planes`
// CV_32FC3 (a, b, c) per pixel or empty (see NormalOptions); `confidence` CV_32FC1 or empty. `camera` must
// already be sized to the image (StereoCamera::resized_to). Throws InputError on
// mismatched sizes or types.
PointCloud build_point_cloud(const cv::Mat& disparity, const cv::Mat& left_rgb,
                             const cv::Mat& planes, const cv::Mat& confidence,
                             const StereoCamera& camera, const CloudFilter& filter = {},
                             const NormalOptions& normals = {});

}  // namespace flexsight
