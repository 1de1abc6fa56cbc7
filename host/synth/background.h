#pragma once
// The picture behind the parts: a random crop of a random library image, resized to the
// output, mirrored at random, and turned with the camera's in-plane rotation, all in one
// affine warp of the source (bilinear; the corners the rotation uncovers are filled by
// reflecting the source at its edges, never black).
#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>

#include "host/render/raycaster.h"
#include "host/synth/background_library.h"

namespace flexsight {

// How the crop is drawn (the generators' settings hold the values and their reasons:
// full_synthetic_settings.h).
struct BackgroundCropSettings {
  double min_crop_scale = 0.5;          // crop's shorter side over the largest that fits
  double max_crop_aspect_change = 0.1;  // log of the crop's aspect change
  double flip_probability = 0.5;        // chance the picture is mirrored left-right
};

// CV_8UC3 RGB of camera.width x camera.height for image (seed, image_index).
// `camera_rotation` is the camera's turn about its optical axis (rotation about z):
// the picture turns about the principal point as the rendered parts do.
cv::Mat draw_background(const BackgroundCropSettings& settings, const BackgroundLibrary& library,
                        const PinholeCamera& camera, const Eigen::Matrix3d& camera_rotation,
                        std::uint32_t seed, std::int64_t image_index);

}  // namespace flexsight
