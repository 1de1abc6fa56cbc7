// A rendered stereo pair of one slanted textured plane: PatchMatch must recover the
// disparity within half a pixel on at least 95 % of the non-occluded pixels.
#include <gtest/gtest.h>

#include "host/stereo/stereo_pipeline.h"
#include "tests/common/test_support.h"

using namespace flexsight;

namespace {

struct RenderedPlane {
  cv::Mat left, right, disparity;  // disparity: true left-view disparity
};

// Left pixel (x, y) shows texture point (x, y); with d(x, y) = a x + b y + c it appears
// in the right image at x - d, so right pixel x' shows texture point
// x = (x' + b y + c) / (1 - a).
RenderedPlane render_slanted_plane(int width, int height, double a, double b, double c) {
  testing_support::ValueNoiseTexture texture(width + 64, height, 3.0f, 21);
  RenderedPlane pair{cv::Mat(height, width, CV_8UC3), cv::Mat(height, width, CV_8UC3),
                     cv::Mat(height, width, CV_32F)};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      pair.left.at<cv::Vec3b>(y, x) = texture.sample(x, y);
      pair.right.at<cv::Vec3b>(y, x) = texture.sample((x + b * y + c) / (1 - a), y);
      pair.disparity.at<float>(y, x) = static_cast<float>(a * x + b * y + c);
    }
  }
  return pair;
}

double share_within_half_pixel(const cv::Mat& estimate, const cv::Mat& truth) {
  int visible = 0, good = 0;
  for (int y = 0; y < truth.rows; ++y) {
    for (int x = 0; x < truth.cols; ++x) {
      float d = truth.at<float>(y, x);
      if (x - d < 0) continue;  // occluded: not visible in the right image
      ++visible;
      if (std::fabs(estimate.at<float>(y, x) - d) <= 0.5f) ++good;
    }
  }
  return static_cast<double>(good) / visible;
}

class SlantedPlane : public ::testing::TestWithParam<StereoMethod> {};

}  // namespace

TEST_P(SlantedPlane, RecoversTheDisparityWithinHalfAPixel) {
  RenderedPlane pair = render_slanted_plane(160, 120, 0.06, 0.03, 8.0);
  StereoParams params;
  params.method = GetParam();
  params.ndisp = 32;
  params.threads = 2;
  StereoResult result = run_stereo(pair.left, pair.right, params);
  EXPECT_GE(share_within_half_pixel(result.disparity, pair.disparity), 0.95);
  if (GetParam() == StereoMethod::PPMS) {
    // The pyramid converges before post-processing; flat PMS with its three checkerboard
    // iterations reaches about 89 % raw and needs the weighted median to pass.
    EXPECT_GE(share_within_half_pixel(result.raw_left, pair.disparity), 0.95);
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, SlantedPlane,
                         ::testing::Values(StereoMethod::PPMS, StereoMethod::PMS),
                         [](const auto& info) { return std::string(method_name(info.param)); });

