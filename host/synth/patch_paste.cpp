#include "host/synth/patch_paste.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace flexsight {

PlacedPatch place_patch(const Patch& patch, const PatchPlacement& placement, cv::Size size) {
  // Patch pixel p maps to centre + scale * Rot(angle) * Mirror * (p - patch centre).
  const cv::Point2d patch_centre((patch.rgb.cols - 1) / 2.0, (patch.rgb.rows - 1) / 2.0);
  cv::Mat transform = cv::getRotationMatrix2D(patch_centre, placement.angle_degrees,
                                              placement.scale);
  if (placement.mirror) {
    // Mirror about the patch's vertical centre line first: x -> 2 cx - x.
    transform.at<double>(0, 2) += transform.at<double>(0, 0) * 2 * patch_centre.x;
    transform.at<double>(1, 2) += transform.at<double>(1, 0) * 2 * patch_centre.x;
    transform.at<double>(0, 0) = -transform.at<double>(0, 0);
    transform.at<double>(1, 0) = -transform.at<double>(1, 0);
  }
  transform.at<double>(0, 2) += placement.centre.x - patch_centre.x;
  transform.at<double>(1, 2) += placement.centre.y - patch_centre.y;

  cv::Mat adjusted;
  patch.rgb.convertTo(adjusted, CV_8UC3, placement.gain,
                      128.0 * (1.0 - placement.gain) + placement.offset);
  PlacedPatch placed;
  const int interpolation = placement.scale < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR;
  cv::warpAffine(adjusted, placed.rgb, transform, size, interpolation, cv::BORDER_CONSTANT);
  cv::Mat coverage;
  patch.mask.convertTo(coverage, CV_32F, 1.0 / 255.0);
  cv::warpAffine(coverage, placed.alpha, transform, size, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  cv::compare(placed.alpha, 0.5, placed.mask, cv::CMP_GT);
  // Softened inwards only: outside the mask the warped colour is the source's own
  // background (black for T-LESS's training images), which must not bleed in as a halo.
  cv::GaussianBlur(placed.alpha, placed.alpha, cv::Size(3, 3), 0.7);
  placed.alpha.setTo(0.0f, placed.mask == 0);
  return placed;
}

void paste_patch(cv::Mat& image, const PlacedPatch& placed) {
  for (int y = 0; y < image.rows; ++y) {
    const float* alpha = placed.alpha.ptr<float>(y);
    const cv::Vec3b* source = placed.rgb.ptr<cv::Vec3b>(y);
    cv::Vec3b* target = image.ptr<cv::Vec3b>(y);
    for (int x = 0; x < image.cols; ++x) {
      const float a = alpha[x];
      if (a <= 0.0f) continue;
      for (int c = 0; c < 3; ++c) {
        target[x][c] = cv::saturate_cast<uchar>(a * source[x][c] + (1.0f - a) * target[x][c]);
      }
    }
  }
}

}  // namespace flexsight
